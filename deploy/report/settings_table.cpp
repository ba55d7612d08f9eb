#include "control/central_core.hpp"
#include "control/group_core.hpp"
#include "control/level2/solver.hpp"
#include "deploy/fleet/config.hpp"
#include "deploy/report/reference.hpp"
#include "plant/plant_config.hpp"

// Every setting outside the scenario, in one table: name, the value a run uses (the default of
// the struct that holds it), unit and meaning. A setting added to one of these structs is added
// here too (tests/unit/test_reference.cpp fails otherwise).
namespace maptr::deploy::report {

namespace {

/// The launcher's waits, waves and leases (FleetConfig).
std::vector<config::Setting> launcher_settings() {
  using config::setting_value;
  const fleet::FleetConfig launcher;
  // clang-format off
  return {
      {"launcher.discovery_timeout_base_s", setting_value(launcher.discovery_timeout_base_s), "s",
       "discovery (every process ready) gives up when no process got ready for base + per_agent x N (4 times that in all)"},
      {"launcher.discovery_timeout_per_agent_s", setting_value(launcher.discovery_timeout_per_agent_s), "s",
       "see discovery_timeout_base_s"},
      {"launcher.wave_size", setting_value(static_cast<int>(launcher.wave_size)), "agents",
       "agents per launch wave"},
      {"launcher.secure_wave_size", setting_value(static_cast<int>(launcher.secure_wave_size)), "agents",
       "agents per launch wave on a secure domain"},
      {"launcher.secure_rematch_s", setting_value(launcher.secure_rematch_s), "s",
       "on a secure domain, processes still not ready this long after discovery's last progress start again"},
      {"launcher.secure_discovery_factor", setting_value(launcher.secure_discovery_factor), "",
       "a secure discovery may take this many times the plain timeout"},
      {"launcher.discovery_death_restarts", setting_value(launcher.discovery_death_restarts), "",
       "a process that ends during discovery is started again at most this many times"},
      {"launcher.rematch_min_s", setting_value(launcher.rematch_min_s), "s",
       "on a plain domain, the unready start again after max(this, one lease) without progress"},
      {"launcher.wave_wait_s", setting_value(launcher.wave_wait_s), "s",
       "the next wave starts when the previous one is ready, or after this long"},
      {"launcher.discovery_listen_s", setting_value(launcher.discovery_listen_s), "s",
       "the discovery server must listen within this long after its start"},
      {"launcher.lease_min_s", setting_value(launcher.lease_min_s), "s",
       "lease of every participant: max(min, per_agent x N)"},
      {"launcher.lease_per_agent_s", setting_value(launcher.lease_per_agent_s), "s", "see lease_min_s"},
      {"launcher.discovery_restart_leases", setting_value(launcher.discovery_restart_leases), "leases",
       "a dead discovery server starts again after this many leases"},
      {"launcher.restart_ready_base_s", setting_value(launcher.restart_ready_base_s), "s",
       "a fault gate waits at most base + per_agent x N for restarted processes to be ready"},
      {"launcher.restart_ready_per_agent_s", setting_value(launcher.restart_ready_per_agent_s), "s",
       "see restart_ready_base_s"},
      {"launcher.restart_unready_retries", setting_value(launcher.restart_unready_retries), "",
       "a process restarted at a fault gate and not ready in time is started again this many times"},
      {"launcher.end_clean_s", setting_value(launcher.end_clean_s), "s",
       "children end on their own after a clean run"},
      {"launcher.end_aborted_s", setting_value(launcher.end_aborted_s), "s", "... after an aborted run"},
      {"launcher.end_term_s", setting_value(launcher.end_term_s), "s", "... after SIGTERM"},
      {"launcher.end_kill_s", setting_value(launcher.end_kill_s), "s", "... after SIGKILL"},
      {"launcher.discovery_term_s", setting_value(launcher.discovery_term_s), "s",
       "the discovery server's time after SIGTERM before SIGKILL"},
      {"launcher.participant_delete_s", setting_value(launcher.participant_delete_s), "s",
       "the launcher's participants' time to be deleted before it writes its results and ends"},
      {"launcher.secure_max_agents", setting_value(launcher.secure_max_agents), "agents",
       "the largest secure fleet (its simple discovery runs over shared memory)"},
  };
  // clang-format on
}

/// The launcher's transport queues and buffers, its stall limit and its polls (FleetConfig).
std::vector<config::Setting> launcher_transport_settings() {
  using config::setting_value;
  const fleet::FleetConfig launcher;
  // clang-format off
  return {
      {"launcher.shm_port_queue", "max(512, 4 x (N + 8))", "samples", "a shared-memory port's queue"},
      {"launcher.recorder_port_queue", "max(8192, 64 x (N + 8))", "samples", "the recorder's port's queue"},
      {"launcher.recorder_udp_buffer_bytes", setting_value(static_cast<int>(launcher.recorder_udp_buffer_bytes)),
       "bytes", "the recorder's UDP receive buffers (other hosts' samples; capped by net.core.rmem_max)"},
      {"launcher.host_plant_loss_s", setting_value(launcher.host_plant_loss_s), "s",
       "on several hosts, how long a process cut off from the plant waits for it"},
      {"launcher.stall_s", setting_value(launcher.stall_s), "s",
       "a run whose plant publishes nothing new this long has stalled and is ended (`--stall-timeout`)"},
      {"launcher.progress_period_s", setting_value(launcher.progress_period_s), "s", "period of the progress line"},
      {"launcher.discovery_poll", setting_value(launcher.discovery_poll), "ms", "poll period of the discovery loop"},
      {"launcher.run_poll", setting_value(launcher.run_poll), "ms", "poll period of the run loop"},
      {"launcher.gate_poll", setting_value(launcher.gate_poll), "ms", "poll period of a fault gate's wait"}
  };
  // clang-format on
}

/// The plant's bounds, deadlines and waits (PlantNodeConfig).
std::vector<config::Setting> plant_settings() {
  using config::setting_value;
  const plant::PlantNodeConfig plant;
  // clang-format off
  return {
      {"plant.deadline_base_s", setting_value(plant.deadline_base_s), "s",
       "the barrier's last-resort deadline per tick: base + per_agent x N (slow is not dead)"},
      {"plant.deadline_per_agent_s", setting_value(plant.deadline_per_agent_s), "s", "see deadline_base_s"},
      {"plant.central_ref_bound_radps", setting_value(plant.central_ref_bound_radps), "rad/s",
       "largest |wheel speed reference| accepted from central"},
      {"plant.central_v_bound_mps", setting_value(plant.central_v_bound_mps), "m/s",
       "largest |body speed reference| accepted from central"},
      {"plant.central_w_bound_radps", setting_value(plant.central_w_bound_radps), "rad/s",
       "largest |yaw rate reference| accepted from central"},
      {"plant.voltage_tolerance_V", setting_value(plant.voltage_tolerance_V), "V",
       "how far above its side's battery voltage an agent's applied voltage may be"},
      {"plant.degraded_band_pct", setting_value(plant.degraded_band_pct), "%",
       "final speed error above which a run that reached its reference ends degraded"},
      {"plant.reached_band_pct", setting_value(plant.reached_band_pct), "%",
       "tracking error under which the reference counts as reached"},
      {"plant.speed_lost_hold_s", setting_value(plant.speed_lost_hold_s), "s",
       "how long the speed stays below stop_below_speed_pct before the run ends"},
      {"plant.gate_timeout_s", setting_value(plant.gate_timeout_s), "s",
       "wall time the plant waits for the launcher at a fault gate"},
      {"plant.resend_s", setting_value(plant.resend_s), "s",
       "wall time after which a tick is sent again to a restarted member that has not answered"},
      {"plant.repair_factor", setting_value(plant.repair_factor), "",
       "a tick is sent again after this many typical barrier times without an answer (a lost sample)"},
      {"plant.repair_min_s", setting_value(plant.repair_min_s), "s", "... and at least this long"},
      {"plant.barrier_average_weight", setting_value(plant.barrier_average_weight), "",
       "weight of the newest tick in the typical barrier time"},
      {"plant.poll", setting_value(plant.poll), "ms",
       "longest wait for a sample in the barrier and a fault gate"},
      {"plant.discovery_poll", setting_value(plant.discovery_poll), "ms",
       "longest wait for a sample in discovery"},
      {"plant.hello_wait", setting_value(plant.hello_wait), "ms",
       "once the fleet is matched, longest wait for the members' hello readers (the hello opens their ports before tick 0)"},
      {"plant.discovery_report", setting_value(plant.discovery_report), "ms",
       "discovery without progress this long: the log names what is not matched"},
      {"plant.linger", setting_value(plant.linger), "ms", "time the last tick gets to reach every reader"}
  };
  // clang-format on
}

/// Central's path follower, the group core's cruise band and the Level-2 solver's tolerances.
std::vector<config::Setting> core_settings() {
  using config::setting_value;
  const control::CentralConfig central;
  const control::GroupConfig group;
  const control::Level2SolverConfig level2;
  // clang-format off
  return {
      {"central.min_lookahead_m", setting_value(central.min_lookahead_m), "m",
       "the path follower's shortest look-ahead L_min (L = max(4 |v| / K, L_min))"},
      {"central.search_ahead_m", setting_value(central.search_ahead_m), "m",
       "the path's nearest point is sought up to the reference's arc length + this"},
      {"group.cruise_enter", setting_value(group.cruise_enter), "1",
       "relative speed error at or below which a side is in cruise (Level 2 decides only then)"},
      {"group.cruise_leave", setting_value(group.cruise_leave), "1",
       "relative speed error above which cruise ends"},
      {"level2.tol", setting_value(level2.tol), "1", "Ipopt's tolerance (scaled KKT error)"},
      {"level2.max_iter", setting_value(level2.max_iter), "",
       "Ipopt's iterations; an unconverged solve's integer choice still compares every count"},
      {"level2.fd_hessian", setting_value(level2.fd_hessian), "",
       "exact Hessian by finite differences (false: limited-memory BFGS)"}
  };
  // clang-format on
}

}  // namespace

std::vector<config::Setting> all_settings() {
  std::vector<config::Setting> all = launcher_settings();
  for (auto part : {launcher_transport_settings(), plant_settings(), core_settings()})
    all.insert(all.end(), part.begin(), part.end());
  return all;
}

}  // namespace maptr::deploy::report
