#pragma once
// The read-only DDS participant of `maptr top`: joins a fleet's domain through its discovery
// server and reads every topic, publishing nothing.
//
// QoS, so that watching never slows the fleet:
// - lock-step topics (ticks, replies, group statuses, central's commands): best effort, volatile,
//   keep-last. The fleet's reliable writers never wait for a best-effort reader (no
//   acknowledgements, no repairs). Depth 1 for ticks and central's commands (only the newest
//   matters), 2 for group statuses (one per side) and the fleet size for agent replies: replies
//   are one DDS instance (no key), so a burst of one tick's replies must fit the history until
//   the listener takes it, or the view would lose agents.
// - events (membership, fault gates, readiness): the fleet's latched profile (reliable,
//   transient-local), so a late joiner sees the deaths that happened before it; a handful of
//   samples per run.
// - UDP on loopback only, no shared memory: the reader shares no shared-memory port (and so no
//   port lock) with any process of the fleet, and a `top` killed at any moment cannot wedge one.
// - no fleet GUID prefix: the fleet's processes do not count it among their own readers.
// Samples are kept only when their writer carries the fleet's id (fleet_id 0: any writer, for
// a replay published by another participant).
//
// A replay (RunInfo::replay_rate > 0) has no fleet to slow down: its lock-step readers are the
// fleet's reliable stream profile with the same depths, so the recording's last tick always
// arrives, and the replay is joined by simple discovery (no discovery server).
#include <memory>
#include <string>

#include "comm/dds/dds.hpp"
#include "deploy/top/fleet_view.hpp"

namespace maptr::top {

/// How to reach a fleet, from its run folder's fleet.json and scenario.
struct FleetCoordinates {
  RunInfo info;
  std::string discovery_server;  ///< HOST:PORT[,HOST:PORT...]
  int discovery_own = -1;        ///< on several hosts: the one server to register with (the plant's host's)
  double lease_s = 2.0;
  uint32_t fleet_id = 0;
  int launcher_pid = 0;
};

/// fleet.json of `run_dir` and the scenario it names; throws std::runtime_error naming the file
/// when it is missing or malformed.
FleetCoordinates read_fleet(const std::string& run_dir);

/// Seconds on the steady clock (the arrival times the view is given).
double steady_now_s();

class FleetReader {
 public:
  explicit FleetReader(const FleetCoordinates& c);
  ~FleetReader();
  FleetReader(const FleetReader&) = delete;
  FleetReader& operator=(const FleetReader&) = delete;

  /// Folds every sample that arrived since the last call into `v`, in arrival order per topic
  /// (events first, then ticks, then what answers them).
  void drain_into(FleetView& v);
  /// Wakes when a sample arrives.
  comm::Signal& signal() { return signal_; }

 private:
  struct Inboxes;
  uint32_t fleet_id_;
  double joined_s_;  ///< system clock, s: events written before it are history
  comm::Signal signal_;
  std::unique_ptr<Inboxes> in_;
  std::unique_ptr<comm::Participant> p_;
};

}  // namespace maptr::top
