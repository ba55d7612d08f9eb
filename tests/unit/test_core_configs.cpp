// Each core's configuration from the scenario (config/core_configs.hpp): every field a core uses
// arrives from its scenario path, and the default scenario's values are those the cores run with.
#include <gtest/gtest.h>

#include "config/core_configs.hpp"

namespace {

using maptr::config::Scenario;

Scenario distinct() {
  Scenario s = maptr::config::parse_scenario(
      "agents: 8\nmode: all\ntick_hz: 200\ntrace_every: 3\n"
      "control: {kp: 3.5, ki: 7, level2_period_s: 2, level2_defer_s: 0.25, horizon: 7, t_on_s: 9,\n"
      "          thermal_limit_s: 33, oracle: true, group_hold_s: 1.5, central_timeout_s: 2.5,\n"
      "          stop_decel_mps2: 1.25, path_heading_gain_1_s: 4.5, path_max_correction_rad_s: 0.6,\n"
      "          fault_detection: true,\n"
      "          fault_current_A: 0.75, fault_jitter_V: 1.5, fault_persistence_s: 0.3, fault_probation_s: "
      "11}\n"
      "faults:\n  - {target: L1, action: fault, at_s: 2, mode: torque, value: 0.5}\n"
      "  - {target: L1, action: clear, at_s: 4}\n  - {target: R0, action: kill, at_s: 3}\n",
      "core-configs.yaml");
  return s;
}

TEST(CoreConfigs, EachCoreGetsItsFieldsFromTheScenario) {
  const Scenario s = distinct();
  const auto agent = maptr::config::agent_config(s);
  EXPECT_DOUBLE_EQ(agent.pid.kp, 3.5);
  EXPECT_DOUBLE_EQ(agent.pid.ki, 7.0);
  EXPECT_DOUBLE_EQ(agent.dt_s, 0.005);
  EXPECT_DOUBLE_EQ(agent.group_hold_s, 1.5);
  EXPECT_DOUBLE_EQ(agent.central_timeout_s, 2.5);
  EXPECT_DOUBLE_EQ(agent.stop_decel_mps2, 1.25);
  const auto group = maptr::config::group_config(s);
  EXPECT_EQ(group.mode, maptr::control::GroupMode::kAll);
  EXPECT_EQ(group.robot.agents, 8);
  EXPECT_DOUBLE_EQ(group.level2_period_s, 2.0);
  EXPECT_DOUBLE_EQ(group.level2_defer_s, 0.25);
  EXPECT_EQ(group.horizon, 7);
  EXPECT_DOUBLE_EQ(group.t_on_s, 9.0);
  EXPECT_DOUBLE_EQ(group.thermal_limit_s, 33.0);
  EXPECT_TRUE(group.oracle);
  EXPECT_TRUE(group.fault_detection);
  EXPECT_DOUBLE_EQ(group.fault_current_A, 0.75);
  EXPECT_DOUBLE_EQ(group.fault_jitter_V, 1.5);
  EXPECT_DOUBLE_EQ(group.fault_persistence_s, 0.3);
  EXPECT_DOUBLE_EQ(group.fault_probation_s, 11.0);
  const auto central = maptr::config::central_config(s);
  EXPECT_DOUBLE_EQ(central.path_heading_gain_1_s, 4.5);
  EXPECT_DOUBLE_EQ(central.path_max_correction_rad_s, 0.6);
  EXPECT_DOUBLE_EQ(central.dt_s, 0.005);
  const auto plant = maptr::config::plant_core_config(s, 1.5, 2.5);
  EXPECT_EQ(plant.trace_every, 3);
  EXPECT_DOUBLE_EQ(plant.speed_lost_hold_s, 1.5);
  EXPECT_DOUBLE_EQ(plant.reached_band_pct, 2.5);
  // The agent's fault and its clear, at their ticks; the process kill is the launcher's.
  ASSERT_EQ(plant.agent_faults.size(), 2u);
  EXPECT_EQ(plant.agent_faults[0].tick, 400);
  EXPECT_EQ(plant.agent_faults[0].side, 0);
  EXPECT_EQ(plant.agent_faults[0].index, 1);
  EXPECT_EQ(plant.agent_faults[0].mode, "torque");
  EXPECT_TRUE(plant.agent_faults[1].clear);
  EXPECT_DOUBLE_EQ(plant.fault_grace_s, 2.0 * 0.3 + 2.0 * 0.005);
}

TEST(CoreConfigs, TheDefaultScenarioDefersLevel2AsItsTableSays) {
  // The scenario's default, not the core struct's own initial value, is what a run uses.
  const Scenario s;
  EXPECT_DOUBLE_EQ(maptr::config::group_config(s).level2_defer_s, s.control.level2_defer_s);
  EXPECT_GT(s.control.level2_defer_s, 0.0);
}

}  // namespace
