#pragma once
// The fleet's own DDS discovery server (maptr_discovery, participant id 0 of its window),
// started first and ended last: clients find only what they need through it. It listens on a
// free UDP port of 127.0.0.1. When it dies during a run the launcher starts it again, once
// every client's lease on the dead server has expired (restart_delay_s later): a client that
// still counts the old server as alive would ignore the new one (its sequence numbers start
// again from 1); one that dropped it registers anew.
#include <chrono>
#include <optional>
#include <string>

#include "deploy/fleet/children.hpp"

namespace maptr::deploy::fleet {

/// A free UDP port on 127.0.0.1 (throws std::runtime_error if there is none).
int free_udp_port();
/// The discovery port of every server of a fleet on several hosts, on DDS domain `domain`.
int host_discovery_port(int domain);

class DiscoveryServer {
 public:
  /// binary: maptr_discovery; listen_s: how long start() waits for it to listen, s.
  DiscoveryServer(const std::string& binary, const std::string& run_dir, int domain, double listen_s,
                  double restart_delay_s);
  /// Server `index` of the comma-separated list `servers` (a fleet on several hosts: one per
  /// host), started through the host's command prefix with its environment; `netns`: the
  /// host's namespace ("" for a real machine, whose listening is not checked).
  DiscoveryServer(const std::string& binary, const std::string& run_dir, int domain, double listen_s,
                  double restart_delay_s, const std::string& servers, int index, const Child& host_like,
                  bool netns);
  ~DiscoveryServer();  ///< kills a server still running (a launch that failed half-way)
  DiscoveryServer(const DiscoveryServer&) = delete;
  DiscoveryServer& operator=(const DiscoveryServer&) = delete;

  const std::string& address() const { return address_; }  ///< "127.0.0.1:PORT"
  int port() const { return port_; }
  pid_t pid() const { return c_.pid; }
  bool running() const { return c_.running; }
  int restarts() const { return restarts_; }

  /// Starts it (again) with a fresh participant id; true once it listens.
  bool start(const Environment& env, ParticipantIds& ids);
  /// Starts it, or throws std::runtime_error with its last error line (after killing a server
  /// that did not listen). The server of a fleet on one host tries up to three free ports.
  void start_or_throw(const Environment& env, ParticipantIds& ids);
  /// A reaped process: true if it was the server. An unexpected death schedules a restart.
  bool on_exit(const Exit& e, bool expected);
  /// Starts it again if a restart is due; returns true if it tried (started tells whether it runs).
  bool restart_if_due(const Environment& env, ParticipantIds& ids, bool& started);
  /// Kills it (a fault).
  void kill_now();
  /// Its host is lost: no restart until release().
  void hold();
  /// Its host is back: a restart is due now if it does not run.
  void release();
  /// Ends it: SIGTERM, then SIGKILL after term_s.
  void stop(double term_s);

 private:
  using Clock = std::chrono::steady_clock;
  /// The server of a fleet on one host listens on 127.0.0.1:port (its address and arguments).
  void use_port(int port);
  Child c_;
  std::string run_dir_, address_;
  int domain_;
  int port_ = 0;
  double listen_s_, restart_delay_s_;
  int restarts_ = 0;
  int index_ = 0, count_ = 1;  ///< its index in the fleet's list of servers, and their number
  bool netns_ = false, remote_ = false, held_ = false;
  std::optional<Clock::time_point> restart_at_;
};

}  // namespace maptr::deploy::fleet
