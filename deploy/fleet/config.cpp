#include "deploy/fleet/config.hpp"

namespace maptr::deploy::fleet {

std::vector<config::Setting> fleet_settings() {
  using config::setting_value;
  const FleetConfig c;
  return {
      {"launcher.discovery_timeout_base_s", setting_value(c.discovery_timeout_base_s), "s",
       "discovery (every process ready) gives up after base + per_agent x N"},
      {"launcher.discovery_timeout_per_agent_s", setting_value(c.discovery_timeout_per_agent_s), "s",
       "see discovery_timeout_base_s"},
      {"launcher.wave_size", setting_value(static_cast<int>(c.wave_size)), "agents",
       "agents per launch wave"},
      {"launcher.secure_wave_size", setting_value(static_cast<int>(c.secure_wave_size)), "agents",
       "agents per launch wave on a secure domain"},
      {"launcher.secure_rematch_s", setting_value(c.secure_rematch_s), "s",
       "on a secure domain, processes still not ready this long after discovery's last progress start again"},
      {"launcher.secure_discovery_factor", setting_value(c.secure_discovery_factor), "",
       "a secure discovery may take this many times the plain timeout"},
      {"launcher.discovery_death_restarts", setting_value(c.discovery_death_restarts), "",
       "a process that ends during discovery is started again at most this many times"},
      {"launcher.rematch_min_s", setting_value(c.rematch_min_s), "s",
       "on a plain domain, the unready start again after max(this, one lease) without progress"},
      {"launcher.wave_wait_s", setting_value(c.wave_wait_s), "s",
       "the next wave starts when the previous one is ready, or after this long"},
      {"launcher.discovery_listen_s", setting_value(c.discovery_listen_s), "s",
       "the discovery server must listen within this long after its start"},
      {"launcher.lease_min_s", setting_value(c.lease_min_s), "s",
       "lease of every participant: max(min, per_agent x N)"},
      {"launcher.lease_per_agent_s", setting_value(c.lease_per_agent_s), "s", "see lease_min_s"},
      {"launcher.discovery_restart_leases", setting_value(c.discovery_restart_leases), "leases",
       "a dead discovery server starts again after this many leases"},
      {"launcher.restart_ready_base_s", setting_value(c.restart_ready_base_s), "s",
       "a fault gate waits at most base + per_agent x N for restarted processes to be ready"},
      {"launcher.restart_ready_per_agent_s", setting_value(c.restart_ready_per_agent_s), "s",
       "see restart_ready_base_s"},
      {"launcher.restart_unready_retries", setting_value(c.restart_unready_retries), "",
       "a process restarted at a fault gate and not ready in time is started again this many times"},
      {"launcher.end_clean_s", setting_value(c.end_clean_s), "s",
       "children end on their own after a clean run"},
      {"launcher.end_aborted_s", setting_value(c.end_aborted_s), "s", "... after an aborted run"},
      {"launcher.end_term_s", setting_value(c.end_term_s), "s", "... after SIGTERM"},
      {"launcher.end_kill_s", setting_value(c.end_kill_s), "s", "... after SIGKILL"},
      {"launcher.discovery_term_s", setting_value(c.discovery_term_s), "s",
       "the discovery server's time after SIGTERM before SIGKILL"},
      {"launcher.participant_delete_s", setting_value(c.participant_delete_s), "s",
       "the launcher's participants' time to be deleted before it writes its results and ends"},
      {"launcher.secure_max_agents", setting_value(c.secure_max_agents), "agents",
       "the largest secure fleet (its simple discovery runs over shared memory)"},
      {"launcher.shm_port_queue", "max(512, 4 x (N + 8))", "samples", "a shared-memory port's queue"},
      {"launcher.recorder_port_queue", "max(8192, 64 x (N + 8))", "samples", "the recorder's port's queue"},
      {"launcher.host_plant_loss_s", setting_value(c.host_plant_loss_s), "s",
       "on several hosts, how long a process cut off from the plant waits for it"},
      {"launcher.stall_s", setting_value(c.stall_s), "s",
       "a run whose plant publishes nothing new this long has stalled and is ended (`--stall-timeout`)"},
      {"launcher.progress_period_s", setting_value(c.progress_period_s), "s", "period of the progress line"},
      {"launcher.discovery_poll", setting_value(c.discovery_poll), "ms", "poll period of the discovery loop"},
      {"launcher.run_poll", setting_value(c.run_poll), "ms", "poll period of the run loop"},
      {"launcher.gate_poll", setting_value(c.gate_poll), "ms", "poll period of a fault gate's wait"},
  };
}

}  // namespace maptr::deploy::fleet
