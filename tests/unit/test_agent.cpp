// Agent core (control/level1/agent_core.hpp): how a newly activated agent joins the running
// ones (every active agent of a side sees the same speed error, so any difference between their
// PID integrators is permanent); what it does when its group or central falls silent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "control/level1/agent_core.hpp"

namespace {

using maptr::control::AgentConfig;
using maptr::control::AgentCore;
using maptr::control::AgentInput;
using maptr::control::AgentOutput;
using maptr::control::AgentState;

/// Tick k of a side cruising near its reference: phidot = ref - 2 cos(0.05 k) rad/s.
AgentInput tick(long long k, bool assigned, double side_V) {
  AgentInput in;
  in.tick = k;
  in.phidot_ref_rad_s = 285.0;
  in.phidot_rad_s = 285.0 - 2.0 * std::cos(0.05 * static_cast<double>(k));
  in.battery_V = 23.4;
  in.central_stamp = k - 1;
  in.group_stamp = k - 1;
  in.assigned = assigned;
  in.side_active_V = side_V;
  return in;
}

TEST(Agent, ANewcomerJoinsAtTheSideVoltageAndStaysLevelWithTheRunningAgents) {
  AgentConfig c;
  AgentCore a(c), b(c);
  double last_a = 0.0;
  for (long long k = 1; k < 100; ++k) {
    last_a = a.step(tick(k, true, k == 1 ? 0.0 : last_a)).voltage_V;
    b.step(tick(k, false, last_a));  // idle: follows the ticks, applies nothing
  }
  ASSERT_GT(last_a, 1.0);
  ASSERT_LT(last_a, 23.4);  // not saturated: the comparison below is exact in that case
  for (long long k = 100; k < 400; ++k) {
    const auto in = tick(k, true, last_a);
    const double va = a.step(in).voltage_V, vb = b.step(in).voltage_V;
    ASSERT_NEAR(va, vb, 1e-9) << "tick " << k;  // same state, same error: same voltage
    last_a = va;
  }
}

TEST(Agent, WithNoActiveAgentOnItsSideANewcomerStartsAtZeroCurrent) {
  AgentConfig c;
  AgentCore a(c);
  a.step(tick(1, false, 0.0));
  const auto in = tick(2, true, 0.0);
  const auto out = a.step(in);
  // Back-EMF preload, then one PID step: V = K_e phidot + K_P e + K_I e dt.
  const double e = in.phidot_ref_rad_s - in.phidot_rad_s;
  const double expected = c.motor.back_emf_Vs * in.phidot_rad_s + c.pid.kp * e + c.pid.ki * e * c.dt_s;
  EXPECT_NEAR(out.voltage_V, std::min(expected, in.battery_V), 1e-9);
}

/// Proportional-only agent (V = ref - phidot at phidot = 0: the voltage shows the reference).
AgentConfig proportional() {
  AgentConfig c;
  c.pid.kp = 1.0;
  c.pid.ki = 0.0;
  c.pid.kd = 0.0;
  return c;
}

/// Tick k at standstill with reference ref, the group's status from tick group_stamp and the
/// central command from tick central_stamp; a battery far above the reference.
AgentInput still(long long k, double ref, long long group_stamp, long long central_stamp) {
  AgentInput in;
  in.tick = k;
  in.phidot_ref_rad_s = ref;
  in.battery_V = 1000.0;
  in.assigned = true;
  in.group_stamp = group_stamp;
  in.central_stamp = central_stamp;
  return in;
}

TEST(Agent, AssignedDrivesAndUnassignedIsOpenCircuit) {
  AgentCore a(proportional());
  const AgentOutput on = a.step(still(1, 10.0, 0, 0));
  EXPECT_EQ(on.state, AgentState::kActive);
  EXPECT_NEAR(on.voltage_V, 10.0, 1e-12);
  AgentInput off = still(2, 10.0, 1, 1);
  off.assigned = false;
  const AgentOutput out = a.step(off);
  EXPECT_EQ(out.state, AgentState::kIdle);
  EXPECT_EQ(out.voltage_V, 0.0);
  EXPECT_FALSE(out.drives());
}

TEST(Agent, SilentGroupHoldsTheLastAssignmentThenCoasts) {
  const AgentConfig c = proportional();  // group_hold_s = 1 s at dt = 10 ms
  AgentCore a(c);
  a.step(still(1, 10.0, 0, 0));
  // The group's last status is from tick 0; central stays fresh.
  const AgentOutput held = a.step(still(51, 10.0, 0, 50));  // group silent for 0.5 s
  EXPECT_EQ(held.state, AgentState::kHolding);
  EXPECT_NEAR(held.voltage_V, 10.0, 1e-12);
  EXPECT_TRUE(held.drives());
  const AgentOutput coast = a.step(still(151, 10.0, 0, 150));  // silent for 1.5 s
  EXPECT_EQ(coast.state, AgentState::kCoasting);
  EXPECT_EQ(coast.voltage_V, 0.0);
  EXPECT_FALSE(coast.drives());
  // The group is back: the agent obeys it again.
  EXPECT_EQ(a.step(still(152, 10.0, 151, 151)).state, AgentState::kActive);
}

TEST(Agent, SilentCentralRampsTheReferenceToZeroAtTheStopDeceleration) {
  const AgentConfig c = proportional();
  AgentCore a(c);
  const double ref = 20.0;
  for (long long k = 1; k <= 10; ++k) a.step(still(k, ref, k - 1, k - 1));
  // Central's last command is from tick 9; the timeout is 1 s = 100 ticks.
  for (long long k = 11; k <= 110; ++k) {
    const AgentOutput out = a.step(still(k, ref, k - 1, 9));
    ASSERT_EQ(out.state, AgentState::kActive) << k;
    ASSERT_NEAR(out.voltage_V, ref, 1e-12) << k;
  }
  // From then on the reference falls by stop_decel / r * dt per tick, to 0, and stays there.
  const double step = c.stop_decel_mps2 / c.wheel_radius_m * c.dt_s;
  double expected = ref;
  for (long long k = 111; k <= 160; ++k) {
    const AgentOutput out = a.step(still(k, ref, k - 1, 9));
    expected = std::max(0.0, expected - step);
    ASSERT_EQ(out.state, AgentState::kStopping) << k;
    ASSERT_NEAR(out.voltage_V, expected, 1e-9) << k;
  }
  EXPECT_EQ(expected, 0.0);
}

}  // namespace
