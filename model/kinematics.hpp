#pragma once
// Skid-steer kinematics. Body frame: x forward, y to the left, left wheels at y = +a/2.
//   v_L = v_x - (a/2) w,  v_R = v_x + (a/2) w    [m/s],   phidot = v / r   [rad/s]
//   v_x = (v_L + v_R) / 2,  w = (v_R - v_L) / a
// a = track (distance between the left and right wheel columns) [m], r = wheel radius [m].
namespace maptr::model {

struct BodyVelocity {
  double v_x = 0.0;  ///< m/s
  double w = 0.0;    ///< rad/s
};

struct WheelSpeeds {
  double v_L = 0.0;  ///< m/s, ground speed of the left wheels
  double v_R = 0.0;  ///< m/s
};

struct WheelRates {
  double phidot_L = 0.0;  ///< rad/s, angular speed of the left wheels
  double phidot_R = 0.0;  ///< rad/s
};

WheelSpeeds to_wheels(const BodyVelocity& b, double track_m);
BodyVelocity to_body(const WheelSpeeds& s, double track_m);

/// Wheel angular speeds of a body velocity: phidot = v_side / r.
WheelRates to_wheel_rates(const BodyVelocity& b, double track_m, double radius_m);
/// Body velocity the wheel angular speeds give (e.g. the body reference from the wheel
/// references): v_x = (phidot_L + phidot_R) r / 2, w = r (phidot_R - phidot_L) / a.
BodyVelocity body_from_rates(const WheelRates& s, double track_m, double radius_m);
/// The forward part of body_from_rates, which needs no track: v_x = (phidot_L + phidot_R) r / 2
/// (e.g. the reference speed from the two sides' wheel-speed references).
double speed_from_rates(const WheelRates& s, double radius_m);

}  // namespace maptr::model
