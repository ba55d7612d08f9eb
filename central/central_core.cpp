#include "central/central_core.hpp"

#include "model/kinematics.hpp"

namespace maptr::central {

CentralOutput CentralCore::step(double t_k, int n_l, int n_r) const {
  CentralOutput o;
  s_.trajectory.reference(t_k + s_.dt(), o.v_x_ref, o.w_ref, o.segment);
  const model::WheelSpeeds ws = model::to_wheels({o.v_x_ref, o.w_ref}, s_.robot.track_m);
  o.phidot_ref_L = ws.v_L / s_.robot.wheel_radius_m;
  o.phidot_ref_R = ws.v_R / s_.robot.wheel_radius_m;
  o.relay_for_L = n_r;
  o.relay_for_R = n_l;
  return o;
}

}  // namespace maptr::central
