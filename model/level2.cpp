#include "model/level2.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "model/dynamics.hpp"
#include "model/motor.hpp"

namespace maptr::model {
namespace {

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

/// Effective inertias, obtained from body_forces() itself (its accelerations are affine in
/// the side torques), so the rollout and the plant cannot disagree:
///   m_eff = m + N I_w / r^2,  I_eff = I_zz + N I_w a^2 / (4 r^2).
struct Inertia {
  double m_eff = 0.0;  ///< kg
  double i_eff = 0.0;  ///< kg m^2
};

Inertia effective_inertia(const RobotParams& rb) {
  const double r = rb.wheel_radius_m, a = rb.track_m;
  const BodyForces zero = body_forces(rb, 0.0, 0.0, 0.0, 0.0);
  const BodyForces push = body_forces(rb, 1.0, 1.0, 0.0, 0.0);   // (tau_L + tau_R)/r = 2/r
  const BodyForces turn = body_forces(rb, -1.0, 1.0, 0.0, 0.0);  // (a/2)(tau_R - tau_L)/r = a/r
  Inertia in;
  in.m_eff = (2.0 / r) / (push.dv_x - zero.dv_x);
  in.i_eff = (a / r) / (turn.dw - zero.dw);
  return in;
}

/// Net side torques (N m) that make the body accelerate by (a_v, a_w) at state (v, w).
void needed_side_torques(const RobotParams& rb, const Inertia& in, double v, double w, double a_v, double a_w,
                         double& tau_l, double& tau_r) {
  const double r = rb.wheel_radius_m, a = rb.track_m;
  const BodyForces f = body_forces(rb, 0.0, 0.0, v, w);  // resistances only
  const double sum = r * (in.m_eff * a_v + f.f_rx);
  const double diff = (2.0 * r / a) * (in.i_eff * a_w + f.m_r);
  tau_l = 0.5 * (sum - diff);
  tau_r = 0.5 * (sum + diff);
}

/// Per-motor voltage the speed loop applies on a side with n active of n_side, V.
double loop_voltage(const Level2Problem& p, double tau_side_needed, double n, double phidot) {
  const MotorParams& m = p.robot.motor;
  const double n_side = p.robot.per_side();
  const double tau_a = (tau_side_needed - (n_side - n) * inactive_torque(m, phidot)) / n;
  return soft_clamp(voltage_for_torque(m, tau_a, phidot), 0.0, p.battery_V, p.clamp_smoothing_V);
}

/// Net side torque with n active motors at voltage V each, N m.
double side_torque(const Level2Problem& p, double n, double voltage, double phidot) {
  const MotorParams& m = p.robot.motor;
  const double n_side = p.robot.per_side();
  const double i_a = armature_current(m, voltage, phidot);
  return n * active_torque(m, i_a, phidot) + (n_side - n) * inactive_torque(m, phidot);
}

}  // namespace

void Level2Problem::validate() const {
  robot.validate();
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
  const MotorParams& mp = rb.motor;
  const double r = rb.wheel_radius_m, a = rb.track_m;
  const Inertia in = effective_inertia(rb);
  const double n_l = p.side == 0 ? n : (p.n_other > 0.0 ? p.n_other : n);
  const double n_r = p.side == 1 ? n : (p.n_other > 0.0 ? p.n_other : n);
  const double v_ref = 0.5 * r * (p.phidot_ref_L + p.phidot_ref_R);
  const double w_ref = r * (p.phidot_ref_R - p.phidot_ref_L) / a;
  const int substeps = std::max(1, static_cast<int>(std::ceil(p.step_s / p.substep_s - 1e-9)));
  const double dt = p.step_s / substeps;

  double v = p.v_x, w = p.w, total = 0.0;
  for (int h = 0; h < p.horizon; ++h) {
    double eta_sum = 0.0;
    for (int s = 0; s < substeps; ++s) {
      // Speed loop: voltages from the state at the substep start, held over the substep.
      const double ph_l = (v - 0.5 * a * w) / r, ph_r = (v + 0.5 * a * w) / r;
      double need_l = 0.0, need_r = 0.0;
      needed_side_torques(rb, in, v, w, (v_ref - v) / p.approach_time_s, (w_ref - w) / p.approach_time_s,
                          need_l, need_r);
      const double volt_l = loop_voltage(p, need_l, n_l, ph_l);
      const double volt_r = loop_voltage(p, need_r, n_r, ph_r);
      eta_sum += p.side == 0 ? efficiency(mp, volt_l, ph_l) : efficiency(mp, volt_r, ph_r);

      // RK4 on (v_x, w) with the voltages held; the currents follow the wheel speeds.
      auto deriv = [&](double vv, double ww, double& dv, double& dw) {
        const double pl = (vv - 0.5 * a * ww) / r, pr = (vv + 0.5 * a * ww) / r;
        const BodyForces b =
            body_forces(rb, side_torque(p, n_l, volt_l, pl), side_torque(p, n_r, volt_r, pr), vv, ww);
        dv = b.dv_x;
        dw = b.dw;
      };
      double k1v, k1w, k2v, k2w, k3v, k3w, k4v, k4w;
      deriv(v, w, k1v, k1w);
      deriv(v + 0.5 * dt * k1v, w + 0.5 * dt * k1w, k2v, k2w);
      deriv(v + 0.5 * dt * k2v, w + 0.5 * dt * k2w, k3v, k3w);
      deriv(v + dt * k3v, w + dt * k3w, k4v, k4w);
      v += dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
      w += dt / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w);
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
  const double v = 0.5 * r * (ph_l + ph_r), w = r * (ph_r - ph_l) / a;
  double need_l = 0.0, need_r = 0.0;
  needed_side_torques(rb, effective_inertia(rb), v, w, 0.0, 0.0, need_l, need_r);
  const double need = p.side == 0 ? need_l : need_r;
  const double phidot = p.side == 0 ? ph_l : ph_r;
  const double tau_a = (need - (rb.per_side() - n) * inactive_torque(rb.motor, phidot)) / n;
  return voltage_for_torque(rb.motor, tau_a, phidot);
}

double feasibility_voltage(const Level2Problem& p, double n) {
  return required_voltage(p, n, 1.0 - p.speed_tolerance);
}

bool level2_feasible(const Level2Problem& p, double n) { return feasibility_voltage(p, n) <= p.battery_V; }

Level2Choice exhaustive_level2(const Level2Problem& p) {
  Level2Choice best;
  if (p.live <= 0) return best;
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

}  // namespace maptr::model
