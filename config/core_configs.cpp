#include "config/core_configs.hpp"

namespace maptr::config {

control::AgentConfig agent_config(const Scenario& s) {
  control::AgentConfig c;
  c.motor = s.robot.motor;
  c.driver = s.robot.driver;
  c.pid = s.control.pid;
  c.wheel_radius_m = s.robot.wheel_radius_m;
  c.dt_s = s.dt();
  c.group_hold_s = s.control.group_hold_s;
  c.central_timeout_s = s.control.central_timeout_s;
  c.stop_decel_mps2 = s.control.stop_decel_mps2;
  return c;
}

control::GroupConfig group_config(const Scenario& s) {
  control::GroupConfig c;
  c.robot = s.robot;
  c.mode = s.mode == "all" ? control::GroupMode::kAll : control::GroupMode::kEnergyConscious;
  c.dt_s = s.dt();
  c.level2_period_s = s.control.level2_period_s;
  c.level2_defer_s = s.control.level2_defer_s;
  c.horizon = s.control.horizon;
  c.horizon_step_s = s.control.horizon_step_s;
  c.t_on_s = s.control.t_on_s;
  c.thermal_limit_s = s.control.thermal_limit_s;
  c.oracle = s.control.oracle;
  c.fault_detection = s.control.fault_detection;
  c.diagnosis.current_A = s.control.fault_current_A;
  c.diagnosis.jitter_V = s.control.fault_jitter_V;
  c.diagnosis.persistence_s = s.control.fault_persistence_s;
  c.diagnosis.probation_s = s.control.fault_probation_s;
  return c;
}

control::CentralConfig central_config(const Scenario& s) {
  control::CentralConfig c;
  c.trajectory = s.trajectory;
  c.dt_s = s.dt();
  c.track_m = s.robot.track_m;
  c.wheel_radius_m = s.robot.wheel_radius_m;
  c.heading_gain_1_s = s.control.path_heading_gain_1_s;
  return c;
}

sim::PlantCoreConfig plant_core_config(const Scenario& sc, double speed_lost_hold_s,
                                       double reached_band_pct) {
  sim::PlantCoreConfig pc;
  pc.robot = sc.robot;
  pc.dt_s = sc.dt();
  pc.trace_every = sc.trace_every;
  pc.initial_discharge_mAh = sc.initial_discharge_mAh;
  pc.stop_below_speed_pct = sc.stop_below_speed_pct;
  pc.speed_lost_hold_s = speed_lost_hold_s;
  pc.reached_band_pct = reached_band_pct;
  pc.trajectory = sc.trajectory;
  for (const auto& f : sc.faults) {
    int side = 0, index = 0;
    if (!is_agent_fault_action(f.action) || !parse_agent_name(f.target, side, index)) continue;
    pc.agent_faults.push_back(
        {first_tick_at(f.at_s, sc.dt()), side, index, f.action == "clear", f.mode, f.value});
  }
  // A detection needs the persistence time of residuals: one that ends within twice that after a
  // clear is the cleared fault's.
  pc.fault_grace_s = 2.0 * sc.control.fault_persistence_s + 2.0 * sc.dt();
  return pc;
}

}  // namespace maptr::config
