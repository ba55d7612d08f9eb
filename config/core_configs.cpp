#include "config/core_configs.hpp"

namespace maptr::config {

control::AgentConfig agent_config(const Scenario& s) {
  control::AgentConfig c;
  static_cast<control::AgentTuning&>(c) = s.control;
  c.motor = s.robot.motor;
  c.driver = s.robot.driver;
  c.wheel_radius_m = s.robot.wheel_radius_m;
  c.dt_s = s.dt();
  return c;
}

control::GroupConfig group_config(const Scenario& s) {
  control::GroupConfig c;
  static_cast<control::GroupTuning&>(c) = s.control;
  c.robot = s.robot;
  c.mode = s.mode == "all" ? control::GroupMode::kAll : control::GroupMode::kEnergyConscious;
  c.dt_s = s.dt();
  return c;
}

control::CentralConfig central_config(const Scenario& s) {
  control::CentralConfig c;
  static_cast<control::CentralTuning&>(c) = s.control;
  c.trajectory = s.trajectory;
  c.dt_s = s.dt();
  c.track_m = s.robot.track_m;
  c.wheel_radius_m = s.robot.wheel_radius_m;
  return c;
}

plant_core::PlantCoreConfig plant_core_config(const Scenario& sc, double speed_lost_hold_s,
                                              double reached_band_pct) {
  plant_core::PlantCoreConfig pc;
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
