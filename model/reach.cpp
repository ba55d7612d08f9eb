#include "model/reach.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "model/dynamics.hpp"
#include "model/kinematics.hpp"
#include "model/motor.hpp"

namespace maptr::model {

namespace {

/// Net torque of a side's n motors all at voltage V and speed phidot, N m.
double side_at(const RobotParams& p, double volts, double phidot) {
  const double i = armature_current(p.motor, p.driver, volts, phidot);
  return p.per_side() * active_torque(p.motor, i, phidot);
}

void side_range(const RobotParams& p, double phidot, double battery_V, double& lo, double& hi) {
  const double v_max = kReachVoltageShare * battery_V;
  hi = side_at(p, v_max, phidot);
  lo = p.driver.bidirectional ? side_at(p, -v_max, phidot)
                              : std::min(side_at(p, 0.0, phidot), p.per_side() * inactive_torque(p.motor, phidot));
}

}  // namespace

TurnCheck steady_turn(const RobotParams& p, double v, double w, double battery_V) {
  TurnCheck c;
  const double r = p.wheel_radius_m, a = p.track_m;
  const BodyForces f = body_resistances(p, v, w);
  const double sum = r * f.f_rx, diff = (2.0 * r / a) * f.m_r;
  c.tau_needed_L = 0.5 * (sum - diff);
  c.tau_needed_R = 0.5 * (sum + diff);
  const WheelRates ph = to_wheel_rates({v, w}, a, r);
  side_range(p, ph.phidot_L, battery_V, c.tau_min_L, c.tau_max_L);
  side_range(p, ph.phidot_R, battery_V, c.tau_min_R, c.tau_max_R);
  c.lateral_accel = std::fabs(v * w);
  auto out = [](double need, double lo, double hi) { return need < lo || need > hi; };
  if (c.lateral_accel > p.mu_lateral * p.gravity)
    c.limit = "lateral acceleration above mu_lateral g";
  else if (out(c.tau_needed_L, c.tau_min_L, c.tau_max_L) || out(c.tau_needed_R, c.tau_min_R, c.tau_max_R))
    c.limit = "side torque out of the driver's reach";
  c.feasible = c.limit.empty();
  return c;
}

double tightest_radius(const RobotParams& p, double v, double battery_V) {
  if (!steady_turn(p, v, 0.0, battery_V).feasible) return std::numeric_limits<double>::infinity();
  // Curvature grows from 0 on a logarithmic grid up to 1 / kMinReachRadius; the first one out of
  // reach is then bisected against the last one held.
  double held = 0.0, lost = 0.0;
  for (double kappa = 1e-4; kappa <= 1.0 / kMinReachRadius * 1.0001; kappa *= 1.25) {
    if (!steady_turn(p, v, v * kappa, battery_V).feasible) {
      lost = kappa;
      break;
    }
    held = kappa;
  }
  if (lost == 0.0) return 0.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (held + lost);
    (steady_turn(p, v, v * mid, battery_V).feasible ? held : lost) = mid;
  }
  return held > 0.0 ? 1.0 / held : std::numeric_limits<double>::infinity();
}

}  // namespace maptr::model
