// Plant core (plant_core/plant_core.hpp): integration of held inputs tick by tick, the ledgers, and
// what each tick reports for the trace and the assignments.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "model/battery.hpp"
#include "model/dynamics.hpp"
#include "model/motor.hpp"
#include "plant_core/plant_core.hpp"
#include "tests/unit/test_support.hpp"

namespace {

using namespace maptr;
using plant_core::AgentApplied;
using plant_core::PlantCore;
using plant_core::PlantCoreConfig;

PlantCoreConfig config(double dt_s) {
  PlantCoreConfig c;
  c.dt_s = dt_s;
  c.initial_discharge_mAh = 100.0;
  return c;
}

std::vector<AgentApplied> driving(int n, double volts) {
  std::vector<AgentApplied> v(n);
  for (auto& a : v) a = {true, true, volts, 0.5, 0.7};
  return v;
}

/// Body speed at which the motors at `volts` balance the losses: dv_x/dt = 0 (straight line).
double steady_speed(const model::RobotParams& p, double volts) {
  model::Inputs u(p.per_side());
  for (int j = 0; j < p.per_side(); ++j) {
    u.voltage_L[j] = u.voltage_R[j] = volts;
    u.active_L[j] = u.active_R[j] = 1;
  }
  auto accel = [&](double v) {
    model::State x{};
    x[model::kVx] = v;
    model::State dx{};
    model::derivative(p, u, x.data(), dx.data());
    return dx[model::kVx];
  };
  return test::bisect(accel, 1e-6, model::no_load_speed(p.motor, volts) * p.wheel_radius_m, 1e-10);
}

TEST(PlantCore, WithoutVoltageTheRobotStaysAtRestAndDrawsNothing) {
  PlantCore core(config(0.01));
  const int n = model::RobotParams{}.per_side();
  const std::vector<AgentApplied> silent(n), idle(n, AgentApplied{true, false, 12.0, 0.0, 0.0});
  for (int k = 0; k < 200; ++k) core.advance(silent, idle, 0.0, 0.0, n, n);
  EXPECT_EQ(core.tick(), 200);
  EXPECT_DOUBLE_EQ(core.t(), 2.0);
  const auto& x = core.state();
  EXPECT_NEAR(x[model::kVx], 0.0, 1e-12);
  EXPECT_NEAR(x[model::kW], 0.0, 1e-12);
  EXPECT_NEAR(x[model::kX], 0.0, 1e-12);
  EXPECT_NEAR(x[model::kEnergyL] + x[model::kEnergyR], 0.0, 1e-12);
  EXPECT_NEAR(core.drawn_mAh(0), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(x[model::kChargeL], 100.0);
  EXPECT_DOUBLE_EQ(core.battery_V(0), model::battery_voltage(model::BatteryParams{}, 100.0));
  EXPECT_EQ(core.mean_active_agents(), 0.0);
  EXPECT_EQ(core.active_time(1), std::vector<double>(n, 0.0));
}

TEST(PlantCore, ConstantVoltageSpeedRisesMonotonicallyToTheMotorSteadyState) {
  const double dt = 0.05, volts = 12.0;
  PlantCore core(config(dt));
  const model::RobotParams p;
  const int n = p.per_side();
  const double v_star = steady_speed(p, volts);
  double v_prev = 0.0;
  bool monotone = true;
  for (int k = 0; k < 800; ++k) {  // 40 s, several time constants
    core.advance(driving(n, volts), driving(n, volts), 0.0, 0.0, n, n);
    const double v = core.state()[model::kVx];
    monotone &= v > v_prev && v < v_star;
    v_prev = v;
  }
  EXPECT_TRUE(monotone);
  test::record("steady_speed_rel_err", std::fabs(v_prev - v_star) / v_star);
  EXPECT_NEAR(v_prev, v_star, 1e-3 * v_star);
  EXPECT_NEAR(core.state()[model::kW], 0.0, 1e-9);  // symmetric sides: straight line
  EXPECT_DOUBLE_EQ(core.active_voltage(0), volts);
  EXPECT_EQ(core.last_active(0), n);
  EXPECT_DOUBLE_EQ(core.mean_active_agents(), 2.0 * n);
  EXPECT_NEAR(core.active_time(0)[3], 40.0, 1e-9);
}

TEST(PlantCore, EnergyIsTheIntegralOfVoltageTimesCurrent) {
  const double dt = 0.01, volts = 10.0;
  PlantCore core(config(dt));
  const model::RobotParams p;
  const int n = p.per_side();
  // Trapezoid rule on V * I(V, phidot) of every motor at the tick boundaries.
  auto power = [&] {
    return n * volts *
           (model::armature_current(p.motor, {}, volts, core.phidot(0)) +
            model::armature_current(p.motor, {}, volts, core.phidot(1)));
  };
  double energy = 0.0;
  for (int k = 0; k < 500; ++k) {
    const double p0 = power();
    core.advance(driving(n, volts), driving(n, volts), 0.0, 0.0, n, n);
    energy += 0.5 * dt * (p0 + power());
  }
  const auto& x = core.state();
  const double drawn = x[model::kEnergyL] + x[model::kEnergyR];
  test::record("energy_rel_err", std::fabs(drawn - energy) / energy);
  EXPECT_NEAR(drawn, energy, 1e-4 * energy);
  // Charge: the integral of the current, A s -> mAh.
  EXPECT_NEAR(core.drawn_mAh(0) + core.drawn_mAh(1), energy / volts / 3.6, 1e-4 * energy / volts / 3.6);
}

TEST(PlantCore, AssignmentChangeReportedOnlyWhenTheMaskChanges) {
  PlantCore core(config(0.01));
  const int n = 8;
  auto left = driving(n, 6.0), right = driving(n, 6.0);
  auto rec = core.advance(left, right, 0.0, 0.0, n, n);
  ASSERT_EQ(rec.assignments.size(), 2u);  // the first tick sets both sides
  EXPECT_EQ(rec.assignments[0].side, 0);
  EXPECT_EQ(rec.assignments[1].driving, std::vector<uint8_t>(n, 1));
  EXPECT_TRUE(core.advance(left, right, 0.0, 0.0, n, n).assignments.empty());
  left[2].drives = false;  // replied, idle
  rec = core.advance(left, right, 0.0, 0.0, n, n);
  ASSERT_EQ(rec.assignments.size(), 1u);
  EXPECT_EQ(rec.assignments[0].side, 0);
  EXPECT_DOUBLE_EQ(rec.assignments[0].t_s, 0.02);
  EXPECT_EQ(rec.assignments[0].driving, (std::vector<uint8_t>{1, 1, 0, 1, 1, 1, 1, 1}));
  right[5] = AgentApplied{};  // no reply: not driving
  rec = core.advance(left, right, 0.0, 0.0, n, n);
  ASSERT_EQ(rec.assignments.size(), 1u);
  EXPECT_EQ(rec.assignments[0].side, 1);
  EXPECT_TRUE(core.advance(left, right, 1.0, 1.0, n, n).assignments.empty());  // a new reference alone
}

TEST(PlantCore, TraceRowIsTheStateAtTkAndTheInputsOverTheTick) {
  PlantCoreConfig c = config(0.01);
  c.trace_every = 3;
  PlantCore core(c);
  const int n = 8;
  auto left = driving(n, 6.0);
  left[0].voltage_V = 12.0;
  left[7].drives = false;
  std::vector<long long> traced;
  for (int k = 0; k < 7; ++k) {
    const model::State before = core.state();
    const auto rec = core.advance(left, driving(n, 6.0), 10.0, 11.0, 7, 6);
    if (!rec.row) continue;
    traced.push_back(rec.row->tick);
    EXPECT_EQ(rec.row->x, before);
    EXPECT_DOUBLE_EQ(rec.row->t_s, k * 0.01);
    EXPECT_DOUBLE_EQ(rec.row->voltage_mean_V[0], (12.0 + 6 * 6.0) / 7);
    EXPECT_DOUBLE_EQ(rec.row->current_A[0], 7 * 0.5);
    EXPECT_DOUBLE_EQ(rec.row->efficiency_mean[1], 0.7);
    EXPECT_EQ(rec.row->n_active[0], 7);
    EXPECT_EQ(rec.row->n_active[1], 8);
    EXPECT_EQ(rec.row->n_live[1], 6);
    EXPECT_DOUBLE_EQ(rec.row->ref_radps[1], 11.0);
  }
  EXPECT_EQ(traced, (std::vector<long long>{0, 3, 6}));
}

TEST(PlantCore, HoldThenIntegrateIsAdvance) {
  PlantCore a(config(0.01)), b(config(0.01));
  const int n = 8;
  for (int k = 0; k < 20; ++k) {
    const auto ra = a.advance(driving(n, 8.0), driving(n, 9.0), 1.0, 2.0, n, n);
    const auto rb = b.hold(driving(n, 8.0), driving(n, 9.0), 1.0, 2.0, n, n);
    EXPECT_EQ(b.tick(), k);  // held, not yet integrated
    b.integrate();
    ASSERT_TRUE(ra.row && rb.row);
    EXPECT_EQ(ra.row->x, rb.row->x);
    EXPECT_EQ(ra.assignments.size(), rb.assignments.size());
  }
  EXPECT_EQ(a.state(), b.state());
  EXPECT_EQ(a.mean_active_agents(), b.mean_active_agents());
}

}  // namespace
