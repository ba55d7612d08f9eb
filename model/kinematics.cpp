#include "model/kinematics.hpp"

namespace maptr::model {

WheelSpeeds to_wheels(const BodyVelocity& b, double a) {
  return {b.v_x - 0.5 * a * b.w, b.v_x + 0.5 * a * b.w};
}

BodyVelocity to_body(const WheelSpeeds& s, double a) { return {0.5 * (s.v_L + s.v_R), (s.v_R - s.v_L) / a}; }

WheelRates to_wheel_rates(const BodyVelocity& b, double a, double r) {
  const WheelSpeeds s = to_wheels(b, a);
  return {s.v_L / r, s.v_R / r};
}

BodyVelocity body_from_rates(const WheelRates& s, double a, double r) {
  return {speed_from_rates(s, r), r * (s.phidot_R - s.phidot_L) / a};
}

double speed_from_rates(const WheelRates& s, double r) { return 0.5 * (s.phidot_L + s.phidot_R) * r; }

}  // namespace maptr::model
