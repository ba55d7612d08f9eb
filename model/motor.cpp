#include "model/motor.hpp"

#include <algorithm>
#include <cmath>

namespace maptr::model {

double smooth_sign(double x, double scale) { return std::tanh(x / scale); }

double armature_current(const MotorParams& m, const DriverParams& d, double v, double phidot) {
  const double i = (v - m.back_emf_Vs * phidot) / m.resistance_ohm;
  return d.bidirectional ? i : std::max(0.0, i);
}

double active_torque(const MotorParams& m, double i, double phidot) {
  return m.torque_constant_NmA *
             (i - m.no_load_current_A * smooth_sign(phidot, m.friction_sign_scale_rad_s)) -
         m.viscous_Nms * phidot;
}

double inactive_torque(const MotorParams& m, double phidot) { return -m.viscous_Nms * phidot; }

double side_torque(const MotorParams& m, double n, double n_side, double i, double phidot) {
  return n * active_torque(m, i, phidot) + (n_side - n) * inactive_torque(m, phidot);
}

double torque_per_active(const MotorParams& m, double tau_side, double n, double n_side, double phidot) {
  return (tau_side - (n_side - n) * inactive_torque(m, phidot)) / n;
}

double efficiency(const MotorParams& m, const DriverParams& d, double v, double phidot) {
  const double i = armature_current(m, d, v, phidot);
  const double p_in = v * i;
  const double p_out = active_torque(m, i, phidot) * phidot;
  if (p_in > 0.0) return p_out > 0.0 ? p_out / p_in : 0.0;
  if (p_in < 0.0 && d.regeneration && p_out < 0.0) return p_in / p_out;
  return 0.0;
}

double no_load_speed(const MotorParams& m, double v) {
  // K_T ((V - K_e w)/R - I_0) = b w, with sgn_s ~ 1 at speed.
  const double kt = m.torque_constant_NmA, r = m.resistance_ohm;
  return (kt * v / r - kt * m.no_load_current_A) / (m.viscous_Nms + kt * m.back_emf_Vs / r);
}

double stall_torque(const MotorParams& m, double v) { return m.torque_constant_NmA * v / m.resistance_ohm; }

double voltage_for_torque(const MotorParams& m, double tau, double phidot) {
  const double s = smooth_sign(phidot, m.friction_sign_scale_rad_s);
  const double i = (tau + m.viscous_Nms * phidot) / m.torque_constant_NmA + m.no_load_current_A * s;
  return m.back_emf_Vs * phidot + i * m.resistance_ohm;
}

}  // namespace maptr::model
