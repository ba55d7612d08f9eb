#pragma once
// The launcher's thresholds: wall-clock waits, wave sizes and the lease rule of a fleet of N
// agents. Wall-clock limits only bound how long the launcher waits for processes; they never
// decide what the simulation computes.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <vector>

namespace maptr::deploy::fleet {

struct FleetConfig {
  /// Discovery (every process ready) gives up when no process got ready for base + per_agent
  /// * N s (at most 4 times that in all), s.
  double discovery_timeout_base_s = 30.0;
  double discovery_timeout_per_agent_s = 0.5;
  /// Agents per launch wave (the first wave also carries the plant, central and both groups).
  std::size_t wave_size = 32;
  /// ... on a secure domain, where every pair of participants runs an authentication handshake
  /// and a key exchange, and a start storm on two cores leaves some pairs unmatched.
  std::size_t secure_wave_size = 4;
  /// Processes still not ready this long after the last progress of discovery (a process
  /// ready, a wave started) are started again with fresh participant ids: on a secure domain a
  /// pair whose key exchange was lost never matches otherwise; on a large plain fleet a few
  /// processes were seen never to be matched by the launcher. s; a secure discovery may take
  /// secure_discovery_factor times the plain timeout.
  double secure_rematch_s = 12.0;
  double secure_discovery_factor = 2.0;
  /// A process that ends during discovery (e.g. Fast DDS's assertion in
  /// StatelessWriter::matched_reader_add under DDS Security on a loaded machine) is started
  /// again, as one that never gets ready is, at most this many times; then the run aborts.
  int discovery_death_restarts = 2;
  /// ... on a plain domain: max(rematch_min_s, one lease).
  double rematch_min_s = 20.0;
  /// The next wave starts when the previous one is ready, or after this wall time, s.
  double wave_wait_s = 20.0;
  /// The discovery server must listen on its port within this wall time after its start, s.
  double discovery_listen_s = 10.0;
  /// Lease of every participant, max(lease_min_s, lease_per_agent_s * N), s: on two cores a
  /// large fleet starves participants for seconds.
  double lease_min_s = 2.0;
  double lease_per_agent_s = 0.05;
  /// A dead discovery server starts again after this many leases: by then every client has
  /// dropped it and registers anew with the new one.
  double discovery_restart_leases = 1.5;
  /// A fault gate waits at most base + per_agent * N for killed processes to end and restarted
  /// ones to report ready, s; then the plant goes on.
  double restart_ready_base_s = 30.0;
  double restart_ready_per_agent_s = 0.5;
  /// A process restarted at a fault gate that has not reported ready within restart_ready_s
  /// (its discovery lost on a starved machine) is started again this many times, with a fresh
  /// participant id, each time with the same wait.
  int restart_unready_retries = 1;
  /// End of a run: wall time the children get to end on their own after a clean run, s.
  double end_clean_s = 10.0;
  /// ... after an aborted run (they have not seen a last tick), s.
  double end_aborted_s = 0.5;
  /// ... after SIGTERM, then after SIGKILL, s.
  double end_term_s = 3.0;
  double end_kill_s = 5.0;
  /// The discovery server gets this long after SIGTERM before SIGKILL, s.
  double discovery_term_s = 3.0;
  /// The launcher's participants get this long to be deleted, s; a deletion still running then
  /// (a deadlock inside Fast DDS 2.9 with security: comm::bound_participant_deletion()) is left,
  /// and the launcher writes its results and ends with _exit.
  double participant_delete_s = 30.0;
  /// A secure fleet's simple discovery runs over shared memory (the loopback interface carries
  /// no multicast): up to this many agents.
  int secure_max_agents = 64;
  /// Messages a shared-memory listening port holds: room for every answer of a tick, several
  /// times over (the plant's port takes one from each agent, group and central per tick).
  int shm_port_queue(int agents) const { return std::max(512, 4 * (agents + 8)); }
  /// ... the recorder's port: it takes every sample of the fleet on one thread, and on a
  /// saturated machine that thread may wait tens of milliseconds for a core; a sample pushed
  /// into a full port is lost to run.mcap.
  int recorder_port_queue(int agents) const { return std::max(8192, 64 * (agents + 8)); }
  /// The recorder's UDP receive buffers, bytes: on several hosts the other hosts' samples reach it
  /// over UDP, in bursts of a tick's answers, and a sample that finds the buffer full is lost to
  /// run.mcap (the kernel caps the size at net.core.rmem_max; Debian's default is 208 KiB).
  uint32_t recorder_udp_buffer_bytes = 8u << 20;
  /// A fleet on several hosts: how long a process cut off from the plant (a partition) waits
  /// for it to come back before it ends, s.
  double host_plant_loss_s = 120.0;
  /// A run whose plant publishes no new tick and no fault gate for this wall time has stalled
  /// and is ended (status "aborted: stalled: ..."), s: longer than any wait of the plant itself
  /// (a fault gate's 120 s, the barrier's deadline) and of a fault gate (restart_ready_s).
  double stall_s = 180.0;
  /// Period of the progress line, s.
  double progress_period_s = 1.0;
  /// Poll periods of the discovery loop, the run loop and a fault gate's wait.
  std::chrono::milliseconds discovery_poll{50};
  std::chrono::milliseconds run_poll{20};
  std::chrono::milliseconds gate_poll{10};

  double discovery_timeout_s(int agents) const {
    return discovery_timeout_base_s + discovery_timeout_per_agent_s * agents;
  }
  double lease_s(int agents) const { return std::max(lease_min_s, lease_per_agent_s * agents); }
  /// Wall time without progress of discovery after which the unready processes start again, s.
  double rematch_s(int agents, bool secure) const {
    return secure ? secure_rematch_s : std::max(rematch_min_s, lease_s(agents));
  }
  double restart_ready_s(int agents) const {
    return restart_ready_base_s + restart_ready_per_agent_s * agents;
  }
};

}  // namespace maptr::deploy::fleet
