#pragma once
// What turns the robot can hold: steady-state turning of a skid-steer robot (docs/MODEL.md
// "Reach"). In a steady turn at speed v and yaw rate w the sides must give
//   tau_L + tau_R = r F_rx(v, w),   tau_R - tau_L = (2 r / a) M_r(v, w)       [N m]
// (model/dynamics.hpp: rolling resistance and the lateral friction moment). A side of n motors
// at wheel speed phidot gives at most n K_T ((m V_B - K_e phidot)/Omega - I_0 sgn) - n b phidot and
// at least the same at the driver's floor: -m V_B with an H-bridge, 0 V (or open circuit) with a
// unidirectional driver, which cannot brake. m = kReachVoltageShare keeps a margin for the
// speed loop. The lateral acceleration v^2 / R must also stay within mu_l g.
#include <string>

#include "model/params.hpp"

namespace maptr::model {

/// Share of the battery voltage the reach check lets a steady turn use (the rest is the speed
/// loop's margin for the transients).
inline constexpr double kReachVoltageShare = 0.9;

struct TurnCheck {
  bool feasible = false;
  double tau_needed_L = 0.0, tau_needed_R = 0.0;  ///< N m, the sides' net torques in the turn
  double tau_min_L = 0.0, tau_max_L = 0.0;        ///< N m, what the left side can give
  double tau_min_R = 0.0, tau_max_R = 0.0;        ///< N m
  double lateral_accel = 0.0;                     ///< m/s^2, v |w|
  std::string limit;  ///< what is out of reach ("" when feasible)
};

/// Whether the robot (every agent of each side active) holds speed v [m/s] at yaw rate w
/// [rad/s] with battery voltage battery_V [V].
TurnCheck steady_turn(const RobotParams& p, double v, double w, double battery_V);

/// The tightest radius [m] the robot holds at speed v > 0 (left and right alike); 0 when every
/// radius down to kMinReachRadius is held, +inf when not even a straight line is.
inline constexpr double kMinReachRadius = 0.01;
double tightest_radius(const RobotParams& p, double v, double battery_V);

}  // namespace maptr::model
