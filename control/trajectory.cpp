#include "control/trajectory.hpp"

#include <algorithm>
#include <cmath>

namespace maptr::control {

double Trajectory::total_duration() const {
  double t = 0.0;
  for (const auto& s : segments) t += s.duration_s;
  return t;
}

void Trajectory::reference(double t, double& v, double& w, int& seg) const {
  double start = 0.0;
  v = 0.0;
  w = 0.0;
  seg = static_cast<int>(segments.size());
  for (std::size_t i = 0; i < segments.size(); ++i) {
    if (t < start + segments[i].duration_s) {
      v = segments[i].speed_mps;
      w = segments[i].yaw_rate_rad_s;
      seg = static_cast<int>(i);
      break;
    }
    start += segments[i].duration_s;
  }
  if (accel_mps2 > 0.0 && seg == 0) v = std::copysign(std::min(std::fabs(v), accel_mps2 * t), v);
}

}  // namespace maptr::control
