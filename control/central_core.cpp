#include "control/central_core.hpp"

#include <algorithm>
#include <cmath>

#include "model/kinematics.hpp"

namespace maptr::control {

CentralOutput CentralCore::step(const CentralInput& in) const {
  CentralOutput o;
  const PathRef ref = path_.at_time(in.t_s + c_.dt_s);
  o.v_x_ref = ref.v;
  o.w_ref = ref.w;
  o.segment = ref.segment;
  if (ref.v > 0.0) {
    const Projection p = path_.project(in.pose, ref.s + c_.search_ahead_m);
    const double k = c_.path_heading_gain_1_s;
    const double z = c_.path_damping;
    const double lookahead = std::max(4.0 * z * z * std::fabs(in.v_x) / k, c_.min_lookahead_m);
    const double wanted = p.on_path.theta - std::atan(p.cross_track / lookahead);
    const double correction = std::clamp(k * wrap_angle(wanted - in.pose.theta),
                                         -c_.path_max_correction_rad_s, c_.path_max_correction_rad_s);
    o.w_ref = ref.v * p.kappa + correction;
    if (o.w_ref == 0.0) o.w_ref = 0.0;  // never -0: the command on a straight line is the profile's
    o.cross_track_m = p.cross_track;
  }
  const model::WheelRates wr = model::to_wheel_rates({o.v_x_ref, o.w_ref}, c_.track_m, c_.wheel_radius_m);
  o.phidot_ref_L = wr.phidot_L;
  o.phidot_ref_R = wr.phidot_R;
  o.relay_for_L = in.n_active_R;
  o.relay_for_R = in.n_active_L;
  return o;
}

}  // namespace maptr::control
