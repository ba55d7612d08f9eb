#include "plant/plant_config.hpp"

namespace maptr::plant {

std::vector<config::Setting> plant_settings() {
  using config::setting_value;
  const PlantNodeConfig c;
  return {
      {"plant.deadline_base_s", setting_value(c.deadline_base_s), "s",
       "the barrier's last-resort deadline per tick: base + per_agent x N (slow is not dead)"},
      {"plant.deadline_per_agent_s", setting_value(c.deadline_per_agent_s), "s", "see deadline_base_s"},
      {"plant.central_ref_bound_radps", setting_value(c.central_ref_bound_radps), "rad/s",
       "largest |wheel speed reference| accepted from central"},
      {"plant.central_v_bound_mps", setting_value(c.central_v_bound_mps), "m/s",
       "largest |body speed reference| accepted from central"},
      {"plant.central_w_bound_radps", setting_value(c.central_w_bound_radps), "rad/s",
       "largest |yaw rate reference| accepted from central"},
      {"plant.voltage_tolerance_V", setting_value(c.voltage_tolerance_V), "V",
       "how far above its side's battery voltage an agent's applied voltage may be"},
      {"plant.degraded_band_pct", setting_value(c.degraded_band_pct), "%",
       "final speed error above which a run that reached its reference ends degraded"},
      {"plant.reached_band_pct", setting_value(c.reached_band_pct), "%",
       "tracking error under which the reference counts as reached"},
      {"plant.speed_lost_hold_s", setting_value(c.speed_lost_hold_s), "s",
       "how long the speed stays below stop_below_speed_pct before the run ends"},
      {"plant.gate_timeout_s", setting_value(c.gate_timeout_s), "s",
       "wall time the plant waits for the launcher at a fault gate"},
      {"plant.resend_s", setting_value(c.resend_s), "s",
       "wall time after which a tick is sent again to a restarted member that has not answered"},
      {"plant.repair_factor", setting_value(c.repair_factor), "",
       "a tick is sent again after this many typical barrier times without an answer (a lost sample)"},
      {"plant.repair_min_s", setting_value(c.repair_min_s), "s", "... and at least this long"},
      {"plant.barrier_average_weight", setting_value(c.barrier_average_weight), "",
       "weight of the newest tick in the typical barrier time"},
      {"plant.poll", setting_value(c.poll), "ms",
       "longest wait for a sample in the barrier and a fault gate"},
      {"plant.discovery_poll", setting_value(c.discovery_poll), "ms",
       "longest wait for a sample in discovery"},
      {"plant.discovery_report", setting_value(c.discovery_report), "ms",
       "discovery without progress this long: the log names what is not matched"},
      {"plant.linger", setting_value(c.linger), "ms", "time the last tick gets to reach every reader"},
  };
}

}  // namespace maptr::plant
