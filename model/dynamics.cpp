#include "model/dynamics.hpp"

#include <algorithm>
#include <cmath>

#include "model/kinematics.hpp"
#include "model/motor.hpp"

namespace maptr::model {
namespace {
constexpr double kTwoOverPi = 2.0 / M_PI;
}

namespace {
/// One active motor's current, torque and losses into s (with the driver's accounting).
void add_active(SideLoad& s, const MotorParams& m, const DriverParams& d, double v, double phidot, double sgn,
                double& brake_A, double& brake_W) {
  const double cur = armature_current(m, d, v, phidot);
  const double p = v * cur;
  s.torque_Nm += active_torque(m, cur, phidot);
  if (p >= 0.0) {
    s.current_A += d.bidirectional ? std::fabs(cur) : cur;
    s.power_W += p;
  } else {
    brake_A += std::fabs(cur);
    brake_W -= p;
  }
  s.joule_W += cur * cur * m.resistance_ohm;
  s.motor_loss_W += (m.torque_constant_NmA * m.no_load_current_A * sgn + m.viscous_Nms * phidot) * phidot;
  s.emf_loss_W += (m.back_emf_Vs - m.torque_constant_NmA) * cur * phidot;
}

/// A motor whose winding is shorted: the current circulates through the short.
void add_shorted(SideLoad& s, const MotorParams& m, double phidot, double sgn) {
  const double cur = -m.back_emf_Vs * phidot / m.resistance_ohm;
  s.torque_Nm += active_torque(m, cur, phidot);
  s.joule_W += cur * cur * m.resistance_ohm;
  s.motor_loss_W += (m.torque_constant_NmA * m.no_load_current_A * sgn + m.viscous_Nms * phidot) * phidot;
  s.emf_loss_W += (m.back_emf_Vs - m.torque_constant_NmA) * cur * phidot;
}
}  // namespace

SideLoad side_load(const MotorParams& m, const DriverParams& d, const std::vector<double>& voltage,
                   const std::vector<uint8_t>& active, double phidot, const std::vector<MotorFault>& faults) {
  SideLoad s;
  const double sgn = smooth_sign(phidot, m.friction_sign_scale_rad_s);
  const double drag = m.viscous_Nms * phidot;
  double brake_A = 0.0, brake_W = 0.0;  // braking motors' current and returned power (>= 0)
  for (std::size_t i = 0; i < active.size(); ++i) {
    const MotorFault* f = faults.empty() || faults[i].healthy() ? nullptr : &faults[i];
    if (active[i] && !f) {
      add_active(s, m, d, voltage[i], phidot, sgn, brake_A, brake_W);
    } else if (active[i]) {
      const MotorParams fm = faulted_params(m, *f);
      const double fsgn = smooth_sign(phidot, fm.friction_sign_scale_rad_s);
      if (f->kind == MotorFaultKind::kShort)
        add_shorted(s, fm, phidot, fsgn);
      else
        add_active(s, fm, d, voltage[i], phidot, fsgn, brake_A, brake_W);
    } else {
      s.torque_Nm += inactive_torque(m, phidot);
      s.motor_loss_W += drag * phidot;
    }
  }
  if (brake_W > 0.0) {
    const double returned = d.regeneration ? std::min(1.0, d.charge_limit_A / brake_A) : 0.0;
    s.current_A -= returned * brake_A;
    s.power_W -= returned * brake_W;
    s.driver_W = (1.0 - returned) * brake_W;
    s.joule_W += s.driver_W;
  }
  return s;
}

EffectiveInertia effective_inertia(const RobotParams& p) {
  const double r = p.wheel_radius_m, a = p.track_m, n = p.agents, iw = p.wheel_inertia();
  return {p.gross_mass_kg + n * iw / (r * r), p.yaw_inertia() + n * iw * a * a / (4.0 * r * r)};
}

double kinetic_energy(const RobotParams& p, double v, double w) {
  const EffectiveInertia in = effective_inertia(p);
  return 0.5 * in.mass_kg * v * v + 0.5 * in.yaw_kgm2 * w * w;
}

double rolling_resistance(const RobotParams& p, double v) {
  return p.mu_rolling * p.gross_mass_kg * p.gravity * kTwoOverPi * std::atan(p.k_s * v);
}

BodyForces body_resistances(const RobotParams& p, double v, double w) {
  const double a = p.track_m;
  const int n = p.agents;
  const WheelSpeeds ws = to_wheels({v, w}, a);
  const double v_l = ws.v_L, v_r = ws.v_R;
  // Rolling resistance: N/2 wheels per side, normal load m g / N each.
  const double per_wheel = p.gross_mass_kg * p.gravity / n;
  const double roll_l = 0.5 * n * p.mu_rolling * per_wheel * kTwoOverPi * std::atan(p.k_s * v_l);
  const double roll_r = 0.5 * n * p.mu_rolling * per_wheel * kTwoOverPi * std::atan(p.k_s * v_r);
  // Lateral friction: 4 wheels per row, lateral speed w x_j.
  double m_lat = 0.0, p_lat = 0.0;
  for (int j = 0; j < p.rows(); ++j) {
    const double xj = p.row_offset(j);
    const double f = 4.0 * p.mu_lateral * per_wheel * kTwoOverPi * std::atan(p.k_s * w * xj);
    m_lat += f * xj;
    p_lat += f * w * xj;
  }
  BodyForces b;
  b.f_rx = roll_l + roll_r;
  b.m_r = m_lat + 0.5 * a * (roll_r - roll_l);
  b.ground_loss_W = roll_l * v_l + roll_r * v_r + p_lat;
  return b;  // dv_x, dw: 0 until with_torques()
}

BodyForces with_torques(const RobotParams& p, const EffectiveInertia& in, const BodyForces& resistances,
                        double tau_l, double tau_r) {
  const double r = p.wheel_radius_m, a = p.track_m;
  BodyForces b = resistances;
  b.dv_x = ((tau_l + tau_r) / r - b.f_rx) / in.mass_kg;
  b.dw = (0.5 * a * (tau_r - tau_l) / r - b.m_r) / in.yaw_kgm2;
  return b;
}

BodyForces body_forces(const RobotParams& p, double tau_l, double tau_r, double v, double w) {
  return with_torques(p, effective_inertia(p), body_resistances(p, v, w), tau_l, tau_r);
}

void derivative(const RobotParams& p, const Inputs& u, const double* x, double* dx) {
  const double r = p.wheel_radius_m, a = p.track_m;
  const double v = x[kVx], w = x[kW], th = x[kTheta];
  const WheelSpeeds ws = to_wheels({v, w}, a);
  const double v_l = ws.v_L, v_r = ws.v_R;
  const SideLoad left = side_load(p.motor, p.driver, u.voltage_L, u.active_L, v_l / r, u.fault_L);
  const SideLoad right = side_load(p.motor, p.driver, u.voltage_R, u.active_R, v_r / r, u.fault_R);
  const BodyForces b = body_forces(p, left.torque_Nm, right.torque_Nm, v, w);

  dx[kX] = v * std::cos(th);
  dx[kY] = v * std::sin(th);
  dx[kTheta] = w;
  dx[kVx] = b.dv_x;
  dx[kW] = b.dw;
  dx[kEnergyL] = left.power_W;
  dx[kEnergyR] = right.power_W;
  dx[kChargeL] = left.current_A / 3.6;  // A -> mAh/s
  dx[kChargeR] = right.current_A / 3.6;
  dx[kPathL] = std::fabs(v_l);
  dx[kPathR] = std::fabs(v_r);
  dx[kDistance] = std::fabs(v);
  dx[kLossJoule] = left.joule_W + right.joule_W;
  dx[kLossMech] = left.motor_loss_W + right.motor_loss_W + b.ground_loss_W;
  dx[kLossEmf] = left.emf_loss_W + right.emf_loss_W;
}

}  // namespace maptr::model
