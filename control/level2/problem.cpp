#include "control/level2/problem.hpp"

#include <algorithm>
#include <cmath>

#include "model/dynamics.hpp"
#include "model/kinematics.hpp"
#include "model/motor.hpp"

namespace maptr::control {
namespace {

using model::armature_current;
using model::body_resistances;
using model::body_from_rates;
using model::BodyForces;
using model::BodyVelocity;
using model::effective_inertia;
using model::EffectiveInertia;
using model::efficiency;
using model::MotorParams;
using model::param_value;
using model::ParamError;
using model::RobotParams;
using model::side_torque;
using model::to_wheel_rates;
using model::torque_per_active;
using model::voltage_for_torque;
using model::WheelRates;
using model::with_torques;

/// Substeps per horizon step: ceil(step_s / substep_s), a ratio this close above an integer
/// counting as that integer.
constexpr double kSubstepSlack = 1e-9;

void require(bool ok, const std::string& field, double value, const std::string& why) {
  if (!ok) throw ParamError("level2." + field + " = " + param_value(value) + ": " + why);
}

/// log(1 + e^x) without overflow.
double softplus(double x) { return x > 0.0 ? x + std::log1p(std::exp(-x)) : std::log1p(std::exp(x)); }

/// Smooth clamp of x to [lo, hi] with width eps (V): a softplus-smoothed max(lo, .) followed
/// by a smoothed min(hi, .). Equals the hard clamp up to eps * e^(-d/eps), d = distance to
/// the nearer limit.
double soft_clamp(double x, double lo, double hi, double eps) {
  const double above_lo = lo + eps * softplus((x - lo) / eps);
  return hi - eps * softplus((hi - above_lo) / eps);
}

/// One classical RK4 step of length dt on (v, w), accel(v, w) giving (dv/dt, dw/dt) and k1 =
/// accel(v, w) given (the caller has the state's forces already).
template <typename Accel>
void horizon_rk4_step(const Accel& accel, const BodyVelocity& k1, double dt, double& v, double& w) {
  const BodyVelocity k2 = accel(v + 0.5 * dt * k1.v_x, w + 0.5 * dt * k1.w);
  const BodyVelocity k3 = accel(v + 0.5 * dt * k2.v_x, w + 0.5 * dt * k2.w);
  const BodyVelocity k4 = accel(v + dt * k3.v_x, w + dt * k3.w);
  v += dt / 6.0 * (k1.v_x + 2.0 * k2.v_x + 2.0 * k3.v_x + k4.v_x);
  w += dt / 6.0 * (k1.w + 2.0 * k2.w + 2.0 * k3.w + k4.w);
}

/// Net side torques (N m) that make the body accelerate by (a_v, a_w) against the resistances
/// f (body_resistances() at the state).
void needed_side_torques(const RobotParams& rb, const EffectiveInertia& in, const BodyForces& f, double a_v,
                         double a_w, double& tau_l, double& tau_r) {
  const double r = rb.wheel_radius_m, a = rb.track_m;
  const double sum = r * (in.mass_kg * a_v + f.f_rx);
  const double diff = (2.0 * r / a) * (in.yaw_kgm2 * a_w + f.m_r);
  tau_l = 0.5 * (sum - diff);
  tau_r = 0.5 * (sum + diff);
}

/// Per-motor voltage the speed loop applies on a side with n active of n_side, V.
double loop_voltage(const Level2Problem& p, double tau_side_needed, double n, double phidot) {
  const MotorParams& m = p.robot.motor;
  const double tau_a = torque_per_active(m, tau_side_needed, n, p.robot.per_side(), phidot);
  return soft_clamp(voltage_for_torque(m, tau_a, phidot), p.robot.driver.floor_V(p.battery_V), p.battery_V,
                    p.clamp_smoothing_V);
}

/// Net side torque with n active motors at voltage V each, N m.
double side_torque_at(const Level2Problem& p, double n, double voltage, double phidot) {
  const MotorParams& m = p.robot.motor;
  return side_torque(m, n, p.robot.per_side(), armature_current(m, p.robot.driver, voltage, phidot), phidot);
}

}  // namespace

void Level2Problem::validate() const {
  require(side == 0 || side == 1, "side", side, "must be 0 (left) or 1 (right)");
  require(live >= 0 && live <= robot.per_side(), "live", live,
          "must be between 0 and the agents per side (" + std::to_string(robot.per_side()) + ")");
  require(std::isfinite(n_other) && n_other <= robot.per_side(), "n_other", n_other,
          "must be finite and at most the agents per side");
  require(std::isfinite(v_x), "v_x", v_x, "must be finite");
  require(std::isfinite(w), "w", w, "must be finite");
  require(std::isfinite(phidot_ref_L), "phidot_ref_L", phidot_ref_L, "must be finite");
  require(std::isfinite(phidot_ref_R), "phidot_ref_R", phidot_ref_R, "must be finite");
  require(std::isfinite(battery_V) && battery_V > 0.0, "battery_V", battery_V, "must be positive");
  require(horizon >= 1 && horizon <= 1000, "horizon", horizon, "must be between 1 and 1000");
  require(std::isfinite(step_s) && step_s > 0.0, "step_s", step_s, "must be positive");
  require(speed_tolerance >= 0.0 && speed_tolerance < 1.0, "speed_tolerance", speed_tolerance,
          "must be in [0, 1)");
  require(std::isfinite(approach_time_s) && approach_time_s > 0.0, "approach_time_s", approach_time_s,
          "must be positive");
  require(std::isfinite(substep_s) && substep_s > 0.0 && substep_s <= step_s, "substep_s", substep_s,
          "must be positive and at most step_s");
  require(std::isfinite(clamp_smoothing_V) && clamp_smoothing_V > 0.0, "clamp_smoothing_V", clamp_smoothing_V,
          "must be positive");
  require(std::isfinite(agent_cost) && agent_cost >= 0.0, "agent_cost", agent_cost, "must be non-negative");
}

double horizon_efficiency(const Level2Problem& p, double n) {
  const RobotParams& rb = p.robot;
  const double r = rb.wheel_radius_m, a = rb.track_m;
  const EffectiveInertia in = effective_inertia(rb);
  const double n_l = p.side == 0 ? n : (p.n_other > 0.0 ? p.n_other : n);
  const double n_r = p.side == 1 ? n : (p.n_other > 0.0 ? p.n_other : n);
  const BodyVelocity ref = body_from_rates({p.phidot_ref_L, p.phidot_ref_R}, a, r);
  const int substeps = std::max(1, static_cast<int>(std::ceil(p.step_s / p.substep_s - kSubstepSlack)));
  const double dt = p.step_s / substeps;

  double v = p.v_x, w = p.w, total = 0.0;
  for (int h = 0; h < p.horizon; ++h) {
    double eta_sum = 0.0;
    for (int s = 0; s < substeps; ++s) {
      // Speed loop: voltages from the state at the substep start, held over the substep.
      const WheelRates ph = to_wheel_rates({v, w}, a, r);
      const BodyForces resist = body_resistances(rb, v, w);
      double need_l = 0.0, need_r = 0.0;
      needed_side_torques(rb, in, resist, (ref.v_x - v) / p.approach_time_s, (ref.w - w) / p.approach_time_s,
                          need_l, need_r);
      const double volt_l = loop_voltage(p, need_l, n_l, ph.phidot_L);
      const double volt_r = loop_voltage(p, need_r, n_r, ph.phidot_R);
      eta_sum += p.side == 0 ? efficiency(rb.motor, rb.driver, volt_l, ph.phidot_L)
                             : efficiency(rb.motor, rb.driver, volt_r, ph.phidot_R);

      // The currents follow the wheel speeds inside the substep; the voltages are held. At the
      // substep start the resistances are the speed loop's (body_forces() to the last bit).
      auto accel_from = [&](const BodyForces& res, const WheelRates& q) {
        const BodyForces b = with_torques(rb, in, res, side_torque_at(p, n_l, volt_l, q.phidot_L),
                                          side_torque_at(p, n_r, volt_r, q.phidot_R));
        return BodyVelocity{b.dv_x, b.dw};
      };
      auto accel = [&](double vv, double ww) {
        return accel_from(body_resistances(rb, vv, ww), to_wheel_rates({vv, ww}, a, r));
      };
      horizon_rk4_step(accel, accel_from(resist, ph), dt, v, w);
    }
    total += eta_sum / substeps;
  }
  return total;
}

double level2_objective(const Level2Problem& p, double n) {
  return horizon_efficiency(p, n) - p.agent_cost * n;
}

double required_voltage(const Level2Problem& p, double n, double speed_scale) {
  const RobotParams& rb = p.robot;
  const double r = rb.wheel_radius_m, a = rb.track_m;
  const double ph_l = speed_scale * p.phidot_ref_L, ph_r = speed_scale * p.phidot_ref_R;
  const BodyVelocity b = body_from_rates({ph_l, ph_r}, a, r);
  double need_l = 0.0, need_r = 0.0;
  needed_side_torques(rb, effective_inertia(rb), body_resistances(rb, b.v_x, b.w), 0.0, 0.0, need_l, need_r);
  const double need = p.side == 0 ? need_l : need_r;
  const double phidot = p.side == 0 ? ph_l : ph_r;
  const double tau_a = torque_per_active(rb.motor, need, n, rb.per_side(), phidot);
  return voltage_for_torque(rb.motor, tau_a, phidot);
}

double steady_side_torque(const Level2Problem& p) {
  const RobotParams& rb = p.robot;
  const BodyVelocity b = body_from_rates({p.phidot_ref_L, p.phidot_ref_R}, rb.track_m, rb.wheel_radius_m);
  double need_l = 0.0, need_r = 0.0;
  needed_side_torques(rb, effective_inertia(rb), body_resistances(rb, b.v_x, b.w), 0.0, 0.0, need_l, need_r);
  return p.side == 0 ? need_l : need_r;
}

bool braking_demand(const Level2Problem& p) {
  return p.robot.driver.bidirectional && steady_side_torque(p) < 0.0;
}

double feasibility_voltage(const Level2Problem& p, double n) {
  return required_voltage(p, n, 1.0 - p.speed_tolerance);
}

bool level2_feasible(const Level2Problem& p, double n) {
  const double v = feasibility_voltage(p, n);
  return v <= p.battery_V && v >= p.robot.driver.floor_V(p.battery_V);
}

Level2Choice exhaustive_level2(const Level2Problem& p) {
  Level2Choice best;
  if (p.live <= 0) return best;
  if (braking_demand(p)) return {p.live, level2_objective(p, p.live), level2_feasible(p, p.live)};
  bool found = false;
  for (int n = 1; n <= p.live; ++n) {
    if (!level2_feasible(p, n)) continue;
    const double j = level2_objective(p, n);
    if (!found || j > best.objective) {  // strict: ties keep the smaller n
      best.n_active = n;
      best.objective = j;
      best.feasible = true;
      found = true;
    }
  }
  if (!found) {
    best.n_active = p.live;
    best.objective = level2_objective(p, p.live);
    best.feasible = false;
  }
  return best;
}

}  // namespace maptr::control
