#pragma once
// The mission: a list of segments of constant body speed v_x [m/s] and yaw rate w [rad/s],
// each lasting duration_s [s], with an optional ramp limit on the speed of the first segment.
// reference(t) is the body reference at simulated time t; after the last segment: stop.
#include <string>
#include <vector>

namespace maptr::control {

/// One piece of the trajectory: constant body speed and yaw rate for a duration.
struct Segment {
  std::string type = "straight";  ///< "straight" | "arc" | "stop"
  double speed_mps = 10.0;        ///< v_x reference, m/s
  double yaw_rate_rad_s = 0.0;    ///< w reference, rad/s (arc: from radius_m if given)
  double duration_s = 60.0;       ///< s
  /// Where the scenario gave it, for messages ("trajectory.segments[1]", or a waypoint's corner
  /// "trajectory.segments[0].points[2]"); "" when made in code.
  std::string origin;
};

struct Trajectory {
  std::vector<Segment> segments{Segment{}};
  double accel_mps2 = 0.0;        ///< ramp limit on the speed reference, m/s^2 (0: steps)
  double total_duration() const;
  /// Reference (v_x, w) at time t; after the last segment: stop (segment = segments.size()).
  void reference(double t, double& v_x, double& w, int& segment) const;
};

}  // namespace maptr::control
