// Agent core (control/level1/agent_core.hpp): how a newly activated agent joins the running
// ones (every active agent of a side sees the same speed error, so any difference between their
// PID integrators is permanent); what it does when its group or central falls silent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "agent/agent_input.hpp"
#include "comm/lockstep/lockstep.hpp"
#include "comm/lockstep/tick_check.hpp"
#include "control/level1/agent_core.hpp"
#include "idl/maptr.h"

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
  // The group's last status is from tick 0; central stays fresh. While the group is silent an
  // agent takes every tick (comm/lockstep/tick_check.hpp).
  AgentOutput held, coast;
  for (long long k = 2; k <= 51; ++k) held = a.step(still(k, 10.0, 0, k - 1));  // silent for 0.5 s
  EXPECT_EQ(held.state, AgentState::kHolding);
  EXPECT_NEAR(held.voltage_V, 10.0, 1e-12);
  EXPECT_TRUE(held.drives());
  for (long long k = 52; k <= 151; ++k) coast = a.step(still(k, 10.0, 0, k - 1));  // silent for 1.5 s
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

/// Tick k of a side of 4 agents as the plant publishes it: agent 2 is assigned in bursts, central
/// falls silent for 2 s (the agents stop) and the group for 1.5 s (they hold, then coast).
maptr::msg::PlantTick side_tick(long long k) {
  namespace msg = maptr::msg;
  const auto speed = [](long long j) { return 285.0 - 2.0 * std::cos(0.05 * static_cast<double>(j)); };
  const auto ref = [](long long j) { return 285.0 + 0.01 * static_cast<double>(j % 500); };
  const auto assigned = [](long long j) { return (j / 37) % 3 == 0 || (j / 11) % 7 == 3; };
  msg::PlantTick t;
  t.tick(static_cast<uint64_t>(k));
  t.run_state(msg::RUN_RUNNING);
  t.central_stamp(k >= 800 && k < 1000 ? 799 : k - 1);
  for (int s = 0; s < 2; ++s) {
    msg::SideTick& side = t.sides()[s];
    side.phidot(speed(k));
    side.phidot_ref(ref(k));
    side.phidot_prev(speed(k > 0 ? k - 1 : k));
    side.phidot_ref_prev(ref(k > 0 ? k - 1 : k));
    side.battery_V(23.4);
    side.V_active(k % 5 == 0 ? 0.0 : 9.0 + std::sin(0.01 * static_cast<double>(k)));
    side.group_stamp(k >= 1340 && k < 1490 ? 1339 : k - 1);
    std::vector<uint8_t> active(4, 0), wake(4, 0);
    active[2] = assigned(k) ? 1 : 0;
    for (int j = 0; j < 4; ++j)
      wake[static_cast<std::size_t>(j)] = active[static_cast<std::size_t>(j)] != 0 || maptr::comm::idle_answer_due(k, s, j, 4);
    side.active(active);
    side.live(std::vector<uint8_t>(4, 1));
    side.wake(wake);
  }
  return t;
}

using maptr::agent::agent_input;

TEST(Agent, TakingOnlyTheFilteredTicksGivesTheSameAnswersAsTakingEvery) {
  // One agent takes every tick, the other only those the tick filter delivers
  // (comm::tick_wakes_agent); at every tick both take, both answer the same, bit for bit.
  AgentCore every{AgentConfig{}}, filtered{AgentConfig{}};
  int taken = 0, compared_active = 0, compared_stopping = 0, compared_holding = 0;
  const long long ticks = 2000;
  for (long long k = 0; k < ticks; ++k) {
    const auto t = side_tick(k);
    const AgentOutput a = every.step(agent_input(t, 0, 2));
    if (!maptr::comm::tick_wakes_agent(t, 0, 2)) {
      ASSERT_FALSE(a.drives()) << "tick " << k << ": the filter held back a tick the agent drives in";
      continue;
    }
    ++taken;
    const AgentOutput b = filtered.step(agent_input(t, 0, 2));
    ASSERT_EQ(a.voltage_V, b.voltage_V) << "tick " << k;
    ASSERT_EQ(a.current_A, b.current_A) << "tick " << k;
    ASSERT_EQ(a.state, b.state) << "tick " << k;
    compared_active += a.state == AgentState::kActive && a.voltage_V > 0.0;
    compared_stopping += a.state == AgentState::kStopping;
    compared_holding += a.state == AgentState::kHolding;
  }
  // The comparison covers each case, and the filter held back a good part of the ticks.
  EXPECT_GT(compared_active, 100);
  EXPECT_GT(compared_stopping, 10);
  EXPECT_GT(compared_holding, 10);
  EXPECT_LT(taken, ticks * 3 / 4);
}

TEST(Agent, ATickLostDuringACentralOutageDoesNotRestartTheSafeStopRamp) {
  // A gap the tick filter did not make (a lost tick) inside an outage of central: the agent goes
  // on with its ramp, not from the reference of the tick before.
  const AgentConfig c = proportional();
  AgentCore a(c);
  const double ref = 20.0;
  for (long long k = 1; k <= 10; ++k) a.step(still(k, ref, k - 1, k - 1));
  AgentOutput out;
  for (long long k = 11; k <= 131; ++k) {
    if (k == 130) continue;  // lost
    AgentInput in = still(k, ref, k - 1, 9);
    in.phidot_ref_prev_rad_s = ref;  // what the plant holds from central's last command
    out = a.step(in);
  }
  // 20 ramp steps of stop_decel / r * dt (0.57 rad/s each) from tick 111 on, less the lost one.
  const double step = c.stop_decel_mps2 / c.wheel_radius_m * c.dt_s;
  EXPECT_EQ(out.state, AgentState::kStopping);
  EXPECT_NEAR(out.voltage_V, ref - 20 * step, 1e-9);
}

TEST(Agent, TheTickFilterDeliversWhatAnAgentNeeds) {
  namespace msg = maptr::msg;
  using maptr::comm::tick_wakes_agent;
  msg::PlantTick t = side_tick(401);  // agent 2 idle (401 / 37 = 10, 401 / 11 = 36), all fresh
  ASSERT_EQ(t.sides()[0].active()[2], 0);
  t.sides()[0].wake()[2] = 0;
  EXPECT_FALSE(tick_wakes_agent(t, 0, 2));
  t.sides()[0].wake()[2] = 1;  // its idle slot, or rejoining
  EXPECT_TRUE(tick_wakes_agent(t, 0, 2));
  t.sides()[0].wake()[2] = 0;
  t.central_stamp(399);  // central's command of tick 400 missing
  EXPECT_TRUE(tick_wakes_agent(t, 0, 2));
  t.central_stamp(400);
  t.sides()[0].group_stamp(399);  // its group's status missing
  EXPECT_TRUE(tick_wakes_agent(t, 0, 2));
  EXPECT_FALSE(tick_wakes_agent(t, 1, 2));  // the other side's group is fresh
  t.sides()[0].group_stamp(400);
  t.run_state(msg::RUN_FINISHED);  // everyone takes the end of the run
  EXPECT_TRUE(tick_wakes_agent(t, 0, 2));
  t.run_state(msg::RUN_RUNNING);
  EXPECT_TRUE(tick_wakes_agent(t, 0, 9));  // out of range: delivered, the follower rejects it
}

}  // namespace
