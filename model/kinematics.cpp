#include "model/kinematics.hpp"

namespace maptr::model {

WheelSpeeds to_wheels(const BodyVelocity& b, double a) {
  return {b.v_x - 0.5 * a * b.w, b.v_x + 0.5 * a * b.w};
}

BodyVelocity to_body(const WheelSpeeds& s, double a) {
  return {0.5 * (s.v_L + s.v_R), (s.v_R - s.v_L) / a};
}

}  // namespace maptr::model
