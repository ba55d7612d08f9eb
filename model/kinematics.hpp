#pragma once
// Skid-steer kinematics (DESIGN "Kinematics"):
//   v_L = v_x - (a/2) w,  v_R = v_x + (a/2) w,  phidot = v / r
//   v_x = (v_L + v_R) / 2, w = (v_R - v_L) / a
// Body frame: x forward, y to the left, left wheels at y = +a/2.
namespace maptr::model {

struct BodyVelocity {
  double v_x = 0.0;  ///< m/s
  double w = 0.0;    ///< rad/s
};

struct WheelSpeeds {
  double v_L = 0.0;  ///< m/s, ground speed of the left wheels
  double v_R = 0.0;  ///< m/s
};

WheelSpeeds to_wheels(const BodyVelocity& b, double track_m);
BodyVelocity to_body(const WheelSpeeds& s, double track_m);

}  // namespace maptr::model
