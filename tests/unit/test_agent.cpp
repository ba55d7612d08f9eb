// Agent core (agent/agent_core.hpp): how a newly activated agent joins the running ones.
// Every active agent of a side sees the same speed error, so any difference between their PID
// integrators is permanent. A newcomer that joins with Pid::align at the side's last voltage has
// the same PID state as the running agents and gives the same voltage at every later tick.
#include <gtest/gtest.h>

#include <cmath>

#include "control/level1/agent_core.hpp"
#include "control/level1/pid.hpp"

namespace {

using maptr::control::AgentConfig;
using maptr::control::AgentCore;
using maptr::control::AgentInput;

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

TEST(Pid, AlignGivesTheSameOutputsAsTheRunningController) {
  maptr::model::PidParams g;
  maptr::control::Pid running(g), joining(g);
  double e_prev = 0.0, v = 0.0;
  for (int k = 0; k < 50; ++k) {
    e_prev = 10.0 * std::cos(0.1 * k);
    v = running.update(e_prev, 0.01, 1e9);
  }
  joining.align(v, e_prev);
  for (int k = 50; k < 200; ++k) {
    const double e = 10.0 * std::cos(0.1 * k);
    EXPECT_NEAR(running.update(e, 0.01, 1e9), joining.update(e, 0.01, 1e9), 1e-12) << k;
  }
}

}  // namespace
