#include "control/central_core.hpp"

#include "model/kinematics.hpp"

namespace maptr::control {

CentralOutput CentralCore::step(double t_k, int n_l, int n_r) const {
  CentralOutput o;
  c_.trajectory.reference(t_k + c_.dt_s, o.v_x_ref, o.w_ref, o.segment);
  const model::WheelRates ref = model::to_wheel_rates({o.v_x_ref, o.w_ref}, c_.track_m, c_.wheel_radius_m);
  o.phidot_ref_L = ref.phidot_L;
  o.phidot_ref_R = ref.phidot_R;
  o.relay_for_L = n_r;
  o.relay_for_R = n_l;
  return o;
}

}  // namespace maptr::control
