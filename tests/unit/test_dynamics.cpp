// Plant dynamics (model/dynamics.hpp): forces, steady states, energy ledger, coast-down.
// Long runs use the CVODE adapter (plant_core/integrator.hpp) in 10 ms ticks, like the plant.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>
#include <string>

#include "model/dynamics.hpp"
#include "model/motor.hpp"
#include "plant_core/integrator.hpp"
#include "tests/unit/test_support.hpp"

namespace {

using maptr::test::record;
using maptr::test::bisect;

namespace mm = maptr::model;
using maptr::plant_core::CvodeIntegrator;

constexpr double kG = 9.81;

// Effective translational mass m + N I_w / r^2 with the disc wheel I_w = m_w r^2 / 2, by hand.
double m_eff_by_hand(double m, int n, double m_w) { return m + n * 0.5 * m_w; }

TEST(Dynamics, RollingResistanceUsesGrossWeightOnceAndKs) {
  // F_rx = sum over N wheels of mu_s (m g / N) (2/pi) atan(k_s v) = mu_s m g (2/pi) atan(k_s v),
  // independent of N (the paper's m g per wheel would make it N times larger).
  for (int n : {4, 16, 128}) {
    mm::RobotParams p;
    p.agents = n;
    const double coulomb = 0.01 * 13.2 * kG;  // 1.29492 N
    // v = 0.01 m/s, k_s = 100 s/m: atan(1) = pi/4, exactly half the Coulomb value (1e-14 relative).
    EXPECT_NEAR(mm::rolling_resistance(p, 0.01), 0.5 * coulomb, 1e-14 * coulomb) << n;
    EXPECT_NEAR(mm::body_forces(p, 0.0, 0.0, 0.01, 0.0).f_rx, 0.5 * coulomb, 1e-14 * coulomb) << n;
    // v = 2 m/s: (2/pi) atan(200) = 1 - 0.00318: within 0.4 % of Coulomb.
    EXPECT_NEAR(mm::body_forces(p, 0.0, 0.0, 2.0, 0.0).f_rx, coulomb * (2.0 / M_PI) * std::atan(200.0),
                1e-14 * coulomb);
    EXPECT_NEAR(mm::rolling_resistance(p, 2.0), coulomb, 0.004 * coulomb);
    EXPECT_EQ(mm::rolling_resistance(p, 0.0), 0.0);
    EXPECT_NEAR(mm::rolling_resistance(p, -1.0), -mm::rolling_resistance(p, 1.0), 1e-15);
  }
  // Effect of k_s: at 0.01 m/s, k_s = 1000 s/m gives (2/pi) atan(10) = 0.9365 of Coulomb.
  mm::RobotParams p;
  p.k_s = 1000.0;
  EXPECT_NEAR(mm::rolling_resistance(p, 0.01), 0.01 * 13.2 * kG * (2.0 / M_PI) * std::atan(10.0), 1e-14);
}

TEST(Dynamics, GeneralNAccelerationWithWheelInertiaOverRSquared) {
  // From rest, net side torques tau each: dv_x/dt = (2 tau / r) / (m + N I_w / r^2), no friction at v = 0.
  // Differential torque: dw/dt = (a/2)(tau_R - tau_L)/r / (I_zz + N I_w a^2 / (4 r^2)). 1e-12 relative.
  for (int n : {4, 16, 64}) {
    mm::RobotParams p;
    p.agents = n;
    const double r = 0.035, a = 0.2, tau = 0.01;
    const double m_eff = m_eff_by_hand(13.2, n, 0.05);
    const mm::BodyForces f = mm::body_forces(p, tau, tau, 0.0, 0.0);
    EXPECT_NEAR(f.dv_x, 2.0 * tau / r / m_eff, 1e-12 * std::fabs(f.dv_x)) << n;
    EXPECT_EQ(f.dw, 0.0);
    const double length = (n / 4) * 0.08;
    const double i_w = 0.5 * 0.05 * r * r;
    const double i_eff = 13.2 * (length * length + a * a) / 12.0 + n * i_w * a * a / (4.0 * r * r);
    const mm::BodyForces g = mm::body_forces(p, 0.0, tau, 0.0, 0.0);
    EXPECT_NEAR(g.dw, 0.5 * a * tau / r / i_eff, 1e-12 * std::fabs(g.dw)) << n;
    EXPECT_NEAR(g.dv_x, tau / r / m_eff, 1e-12 * std::fabs(g.dv_x)) << n;
  }
}

TEST(Dynamics, DerivativeAtAStateAgainstHandEvaluation) {
  // N = 8 (4 per side, 2 rows at +-b/2), left: agents 0,1 active at 10 V; right: agents 0..2 at 12 V.
  mm::RobotParams p;
  p.agents = 8;
  mm::Inputs u(4);
  u.active_L = {1, 1, 0, 0};
  u.voltage_L = {10.0, 10.0, 99.0, 99.0};  // voltages of inactive agents are ignored
  u.active_R = {1, 1, 1, 0};
  u.voltage_R = {12.0, 12.0, 12.0, 0.0};
  mm::State x{};
  x[mm::kTheta] = 0.3;
  x[mm::kVx] = 1.0;
  x[mm::kW] = 0.5;
  mm::State dx{};
  mm::derivative(p, u, x.data(), dx.data());

  const double m = 13.2, n = 8, a = 0.2, b = 0.08, r = 0.035;
  const double kt = 38.2e-3, ke = 38.4e-3, res = 7.03, i0 = 0.05, bv = 6e-7, sc = 0.5;
  const double v_l = 1.0 - 0.1 * 0.5, v_r = 1.0 + 0.1 * 0.5;  // 0.95, 1.05 m/s
  const double ph_l = v_l / r, ph_r = v_r / r;
  const double i_l = (10.0 - ke * ph_l) / res, i_r = (12.0 - ke * ph_r) / res;
  const double tau_l = 2 * (kt * (i_l - i0 * std::tanh(ph_l / sc)) - bv * ph_l) - 2 * bv * ph_l;
  const double tau_r = 3 * (kt * (i_r - i0 * std::tanh(ph_r / sc)) - bv * ph_r) - 1 * bv * ph_r;
  const double per_wheel = m * kG / n;
  const double roll_l = 4 * 0.01 * per_wheel * (2 / M_PI) * std::atan(100 * v_l);
  const double roll_r = 4 * 0.01 * per_wheel * (2 / M_PI) * std::atan(100 * v_r);
  double m_lat = 0.0;
  for (double xj : {-0.5 * b, 0.5 * b}) m_lat += 4 * 0.1 * per_wheel * (2 / M_PI) * std::atan(100 * 0.5 * xj) * xj;
  const double i_w = 0.5 * 0.05 * r * r;
  const double m_eff = m + n * i_w / (r * r);
  const double i_eff = m * ((2 * b) * (2 * b) + a * a) / 12.0 + n * i_w * a * a / (4 * r * r);
  const double dv = ((tau_l + tau_r) / r - roll_l - roll_r) / m_eff;
  const double dw = (0.5 * a * (tau_r - tau_l) / r - m_lat - 0.5 * a * (roll_r - roll_l)) / i_eff;

  // 1e-12 relative (same arithmetic up to ordering).
  EXPECT_NEAR(dx[mm::kX], std::cos(0.3), 1e-15);
  EXPECT_NEAR(dx[mm::kY], std::sin(0.3), 1e-15);
  EXPECT_NEAR(dx[mm::kTheta], 0.5, 1e-15);
  EXPECT_NEAR(dx[mm::kVx], dv, 1e-12 * std::fabs(dv));
  EXPECT_NEAR(dx[mm::kW], dw, 1e-12 * std::fabs(dw));
  EXPECT_NEAR(dx[mm::kEnergyL], 2 * 10.0 * i_l, 1e-12);
  EXPECT_NEAR(dx[mm::kEnergyR], 3 * 12.0 * i_r, 1e-12);
  EXPECT_NEAR(dx[mm::kChargeL], 2 * i_l * 1000.0 / 3600.0, 1e-12);  // A -> mAh/s
  EXPECT_NEAR(dx[mm::kChargeR], 3 * i_r * 1000.0 / 3600.0, 1e-12);
  EXPECT_NEAR(dx[mm::kPathL], 0.95, 1e-15);
  EXPECT_NEAR(dx[mm::kPathR], 1.05, 1e-15);
  EXPECT_NEAR(dx[mm::kDistance], 1.0, 1e-15);
  EXPECT_NEAR(dx[mm::kLossJoule], (2 * i_l * i_l + 3 * i_r * i_r) * res, 1e-12);
  // K_e != K_T: (K_e - K_T) I phidot is the power neither dissipated in R nor delivered to the shaft.
  EXPECT_NEAR(dx[mm::kLossEmf], (ke - kt) * (2 * i_l * ph_l + 3 * i_r * ph_r), 1e-12);
}

TEST(Dynamics, InactiveMotorsDrawNothingAndOnlyDrag) {
  const mm::MotorParams m = mm::motor_type("I");
  const std::vector<double> volts = {24.0, 24.0, 24.0};
  const std::vector<uint8_t> off = {0, 0, 0};
  const mm::SideLoad s = mm::side_load(m, {}, volts, off, 200.0);
  EXPECT_EQ(s.current_A, 0.0);
  EXPECT_EQ(s.power_W, 0.0);
  EXPECT_EQ(s.joule_W, 0.0);
  EXPECT_NEAR(s.torque_Nm, -3 * 6e-7 * 200.0, 1e-18);
  EXPECT_NEAR(s.motor_loss_W, 3 * 6e-7 * 200.0 * 200.0, 1e-15);
}

// ---- Steady-state straight line: hand solution vs a long CVODE run ----------------------------

struct SteadyCase {
  int agents;
  int active_per_side;
  double mass_kg;
  double voltage_V;
  double seconds;
};

class SteadyState : public ::testing::TestWithParam<SteadyCase> {};

TEST_P(SteadyState, SpeedAndCurrentMatchTheHandSolution) {
  const SteadyCase c = GetParam();
  mm::RobotParams p;
  p.agents = c.agents;
  p.gross_mass_kg = c.mass_kg;
  const int ns = c.agents / 2;

  // Hand model (Type I literals): per active motor I = (V - K_e phidot)/R, tau = K_T (I - I_0 tanh(phidot/0.5)) - b phidot;
  // per inactive motor tau = -b phidot. Steady state: 2 tau_side / r = mu_s m g (2/pi) atan(k_s v).
  const double kt = 38.2e-3, ke = 38.4e-3, res = 7.03, i0 = 0.05, bv = 6e-7, r = 0.035;
  auto current = [&](double v) { return std::max(0.0, (c.voltage_V - ke * v / r) / res); };
  auto net_force = [&](double v) {
    const double ph = v / r;
    const double tau_side =
        c.active_per_side * (kt * (current(v) - i0 * std::tanh(ph / 0.5)) - bv * ph) - (ns - c.active_per_side) * bv * ph;
    return 2.0 * tau_side / r - 0.01 * c.mass_kg * kG * (2.0 / M_PI) * std::atan(100.0 * v);
  };
  const double v_star = bisect(net_force, 0.05, c.voltage_V * r / ke, 1e-13);
  const double i_star = c.active_per_side * current(v_star);  // per side, A

  CvodeIntegrator cv(p);
  mm::Inputs u(ns);
  for (int i = 0; i < c.active_per_side; ++i) {
    u.active_L[i] = u.active_R[i] = 1;
    u.voltage_L[i] = u.voltage_R[i] = c.voltage_V;
  }
  mm::State x{};
  const double dt = 0.01;
  const int ticks = static_cast<int>(std::lround(c.seconds / dt));
  double charge_l_1s_before = 0.0;
  for (int k = 0; k < ticks; ++k) {
    if (k == ticks - 100) charge_l_1s_before = x[mm::kChargeL];
    cv.step(x, u, k * dt, dt);
  }
  // Current over the last second from the charge ledger (mAh -> A: * 3.6 / 1 s).
  const double i_run = (x[mm::kChargeL] - charge_l_1s_before) * 3.6 / 1.0;
  const double i_run_r = mm::side_load(p.motor, {}, u.voltage_R, u.active_R, x[mm::kVx] / r).current_A;

  // Tolerances: speed 1e-4 relative, current 1e-4 A (the run lasts > 10 time constants).
  EXPECT_NEAR(x[mm::kVx], v_star, 1e-4 * v_star);
  EXPECT_NEAR(i_run, i_star, 1e-4);
  EXPECT_NEAR(i_run_r, i_star, 1e-4);
  EXPECT_NEAR(x[mm::kW], 0.0, 1e-9);
  const std::string tag = "steady_N" + std::to_string(c.agents) + "_Na" + std::to_string(c.active_per_side);
  record(tag + "_v_star_m_s", v_star);
  record(tag + "_speed_rel_err", (x[mm::kVx] - v_star) / v_star);
  record(tag + "_current_abs_err_A", i_run - i_star);
}

// Time constants m_eff / (n_active K_T K_e / (R r^2)): about 10 s, 10.5 s and 9 s; runs last >= 15 of them.
INSTANTIATE_TEST_SUITE_P(Dynamics, SteadyState,
                         ::testing::Values(SteadyCase{16, 4, 13.2, 12.0, 150.0},
                                           SteadyCase{16, 8, 28.2, 24.0, 160.0},
                                           SteadyCase{32, 10, 30.0, 18.0, 150.0}),
                         [](const ::testing::TestParamInfo<SteadyCase>& i) {
                           return "N" + std::to_string(i.param.agents) + "_Na" +
                                  std::to_string(i.param.active_per_side) + "PerSide_" +
                                  std::to_string(static_cast<int>(i.param.voltage_V)) + "V";
                         });

// ---- Energy ledger ---------------------------------------------------------------------------

TEST(Dynamics, EnergyBalanceWithAccelerationAndTurning) {
  // Energy drawn = Joule + mechanical (ground + motor friction + drag) + K_e/K_T mismatch + kinetic.
  mm::RobotParams p;
  p.gross_mass_kg = 18.2;
  CvodeIntegrator cv(p);
  mm::Inputs u(8);
  mm::State x{};
  const double dt = 0.01;
  double worst = 0.0;
  for (int k = 0; k < 3000; ++k) {  // 30 s
    const double t = k * dt;
    // Changing inputs: 10 s straight (all agents, rising voltage), 10 s hard left turn (1 left agent
    // at 6 V, every right agent at 24 V), 5 s right turn with few agents, 5 s coasting (left off,
    // right voltage below the back-emf: no current).
    const int n_l = t < 10 ? 8 : (t < 20 ? 1 : (t < 25 ? 8 : 0));
    const int n_r = t < 10 ? 8 : (t < 20 ? 8 : (t < 25 ? 2 : 8));
    const double v_l = t < 10 ? 8.0 + 0.5 * t : (t < 20 ? 6.0 : 20.0);
    const double v_r = t < 10 ? 8.0 + 0.5 * t : (t < 20 ? 24.0 : (t < 25 ? 10.0 + 0.3 * std::sin(t) : 1.0));
    for (int i = 0; i < 8; ++i) {
      u.active_L[i] = i < n_l;
      u.active_R[i] = i < n_r;
      u.voltage_L[i] = v_l;
      u.voltage_R[i] = v_r;
    }
    cv.step(x, u, t, dt);
    const double drawn = x[mm::kEnergyL] + x[mm::kEnergyR];
    const double accounted =
        x[mm::kLossJoule] + x[mm::kLossMech] + x[mm::kLossEmf] + mm::kinetic_energy(p, x[mm::kVx], x[mm::kW]);
    if (drawn > 1.0) worst = std::max(worst, std::fabs(drawn - accounted) / drawn);
    EXPECT_NEAR(accounted, drawn, 1e-5 * drawn + 1e-9) << "t = " << t;
  }
  // The run must really accelerate and turn.
  EXPECT_GT(x[mm::kDistance], 10.0);
  EXPECT_GT(std::fabs(x[mm::kTheta]), 1.0);
  record("energy_balance_max_rel_err", worst);
}

TEST(Dynamics, EffectiveInertiasAreTheOnesTheAccelerationsUse) {
  // N = 16: m_eff = 13.2 + 16 * 0.5 * 0.05 = 13.6 kg, I_eff = 0.16064 kg m^2 (below).
  mm::RobotParams p;
  const mm::EffectiveInertia in = mm::effective_inertia(p);
  EXPECT_NEAR(in.mass_kg, 13.6, 1e-12);
  EXPECT_NEAR(in.yaw_kgm2, 0.16064, 1e-12);
  // At rest (no resistance) a push of 1 N m per side gives dv/dt = (2/r) / m_eff, and a turn
  // (-1, +1) N m gives dw/dt = (a/r) / I_eff.
  const double r = p.wheel_radius_m, a = p.track_m;
  EXPECT_NEAR(mm::body_forces(p, 1.0, 1.0, 0.0, 0.0).dv_x, (2.0 / r) / in.mass_kg, 1e-12);
  EXPECT_NEAR(mm::body_forces(p, -1.0, 1.0, 0.0, 0.0).dw, (a / r) / in.yaw_kgm2, 1e-10);
}

TEST(Dynamics, ResistancesThenTorquesAreBodyForcesToTheLastBit) {
  // The Level-2 rollout computes the resistances once per state and applies several torques
  // to them; the plant calls body_forces(). Both must be one model, bit for bit.
  for (int agents : {4, 16, 64}) {
    mm::RobotParams p;
    p.agents = agents;
    const mm::EffectiveInertia in = mm::effective_inertia(p);
    for (double v : {-1.3, 0.0, 0.004, 2.5, 11.0}) {
      for (double w : {-0.8, 0.0, 0.02, 1.7}) {
        const mm::BodyForces res = mm::body_resistances(p, v, w);
        EXPECT_EQ(res.dv_x, 0.0);
        EXPECT_EQ(res.dw, 0.0);
        for (double tl : {-3.0, 0.0, 0.7}) {
          for (double tr : {-0.2, 0.0, 4.1}) {
            const mm::BodyForces a = mm::body_forces(p, tl, tr, v, w);
            const mm::BodyForces b = mm::with_torques(p, in, res, tl, tr);
            EXPECT_EQ(a.dv_x, b.dv_x) << agents << " " << v << " " << w << " " << tl << " " << tr;
            EXPECT_EQ(a.dw, b.dw);
            EXPECT_EQ(a.f_rx, b.f_rx);
            EXPECT_EQ(a.m_r, b.m_r);
            EXPECT_EQ(a.ground_loss_W, b.ground_loss_W);
          }
        }
      }
    }
  }
}

TEST(Dynamics, KineticEnergyClosedForm) {
  // KE = (m + N I_w/r^2) v^2 / 2 + (I_zz + N I_w a^2 / (4 r^2)) w^2 / 2; N = 16: m_eff = 13.6 kg,
  // I_eff = 0.15664 + 16 * 3.0625e-5 * 0.04 / (4 * 0.001225) = 0.16064 kg m^2.
  mm::RobotParams p;
  EXPECT_NEAR(mm::kinetic_energy(p, 2.0, 0.0), 0.5 * 13.6 * 4.0, 1e-12);
  EXPECT_NEAR(mm::kinetic_energy(p, 0.0, 3.0), 0.5 * 0.16064 * 9.0, 1e-12);
  EXPECT_NEAR(mm::kinetic_energy(p, 2.0, 3.0), 0.5 * 13.6 * 4.0 + 0.5 * 0.16064 * 9.0, 1e-12);
}

// ---- Coast-down: inactive motors' drag ------------------------------------------------------

// All motors inactive from v0, straight line. With k_s large the rolling resistance is Coulomb,
//   m_eff dv/dt = -F_c - c v,  F_c = mu_s m g,  c = N b / r^2   (each inactive motor: b phidot),
// so v(t) = (v0 + F_c/c) e^{-c t/m_eff} - F_c/c, and with b = 0: v(t) = v0 - F_c t / m_eff.
TEST(Dynamics, InactiveMotorsSlowTheRobotMoreThanNoMotors) {
  const double v0 = 5.0, T = 20.0, dt = 0.01;
  auto coast = [&](double viscous) {
    mm::RobotParams p;
    p.k_s = 1e6;  // (2/pi) atan(k_s v) = 1 - 2/(pi k_s v): below 2e-7 off for v > 3 m/s
    p.motor.viscous_Nms = viscous;
    CvodeIntegrator cv(p);
    mm::Inputs u(p.per_side());
    mm::State x{};
    x[mm::kVx] = v0;
    for (int k = 0; k < static_cast<int>(T / dt); ++k) cv.step(x, u, k * dt, dt);
    return x[mm::kVx];
  };
  const double v_drag = coast(6e-7), v_free = coast(0.0);

  const double m_eff = m_eff_by_hand(13.2, 16, 0.05);  // 13.6 kg
  const double f_c = 0.01 * 13.2 * kG;
  const double c = 16 * 6e-7 / (0.035 * 0.035);
  const double v_drag_cf = (v0 + f_c / c) * std::exp(-c * T / m_eff) - f_c / c;
  const double v_free_cf = v0 - f_c * T / m_eff;

  EXPECT_LT(v_drag, v_free);
  // Tolerance 1e-5 relative: atan deviation (2e-7 of the friction) and integration error.
  EXPECT_NEAR(v_drag, v_drag_cf, 1e-5 * v_drag_cf);
  EXPECT_NEAR(v_free, v_free_cf, 1e-5 * v_free_cf);
  // The drag's effect itself (about 0.045 m/s here) to 1e-3 relative.
  EXPECT_NEAR(v_free - v_drag, v_free_cf - v_drag_cf, 1e-3 * (v_free_cf - v_drag_cf));
  record("coast_drag_rel_err", (v_drag - v_drag_cf) / v_drag_cf);
  record("coast_free_rel_err", (v_free - v_free_cf) / v_free_cf);
  record("coast_drag_effect_m_s", v_free - v_drag);
}

}  // namespace
