#pragma once
// The fleet launcher: starts every process of a run as a child (plant, central, two groups,
// N agents) around the fleet's DDS discovery server (maptr_discovery), waits until every
// process has matched the topics it needs, starts the lock-step, shows progress, injects the
// scenario's faults at the plant's fault gates, sees children die at once (wait4) and
// publishes it, ends every process, and writes summary.json. Children die with the launcher
// (PR_SET_PDEATHSIG). The units it is made of are in deploy/fleet/.
#include <spdlog/logger.h>

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "config/scenario.hpp"

namespace maptr::deploy {

struct LaunchOptions {
  config::Scenario scenario;
  std::string run_dir;   ///< created if missing
  std::string bin_dir;   ///< where maptr_agent & co. are
  int domain = 0;        ///< DDS domain id
  bool progress = true;  ///< print a progress line every second
  /// Processes the launcher does not start: the user starts them (e.g. on another terminal or
  /// host) with the command printed at launch; the fleet waits for them like for the others.
  std::vector<std::string> external;
  /// Data transport of the fleet: "shm", "shm+udp", "udp" (loopback) or "auto": shared memory
  /// on one host, shared memory and UDP on several hosts or on a secure domain.
  std::string transport = "auto";
  long long chaos_seed = -1;  ///< recorded in the summary when the faults came from --chaos
  /// A secure domain (deploy/fleet/secure_domain.hpp): a private CA, one certificate and
  /// permissions document per process in RUN_DIR/security; simple discovery (no discovery
  /// server: Fast DDS 2.9 has none with DDS Security).
  bool secure = false;
  /// Wall time without a new tick or fault gate from the plant after which the run is ended as
  /// stalled, s; 0: FleetConfig::stall_s.
  double stall_s = 0.0;

  /// The options of a fleet that takes every other option's default.
  static LaunchOptions of(config::Scenario scenario, std::string run_dir, std::string bin_dir, int domain) {
    LaunchOptions o;
    o.scenario = std::move(scenario);
    o.run_dir = std::move(run_dir);
    o.bin_dir = std::move(bin_dir);
    o.domain = domain;
    return o;
  }
};

/// Why options `o` cannot run together (e.g. --secure with a fault of the discovery server it
/// does not start), or "" if they can; the message names the options.
std::string secure_problem(const LaunchOptions& o);

/// Sends "kill NAME" or "restart NAME" to the launcher running in run_dir (through its
/// control FIFO). Throws std::runtime_error when no fleet runs there.
void send_command(const std::string& run_dir, const std::string& action, const std::string& target);

/// Runs the fleet; returns the summary (also written to RUN_DIR/summary.json).
nlohmann::json launch(const LaunchOptions& o, spdlog::logger& log);

/// The start of the status of a fleet whose processes did not all report ready in time; launch()
/// then runs it once more (fresh discovery server, another domain) and the summary says so
/// (`discovery_retry`), keeping the first attempt's files in RUN/first-attempt/.
inline constexpr const char* kDiscoveryTimeout = "aborted: discovery timed out";

/// Why a fleet of `agents` agents cannot run on DDS `domain` (its participants' ports would go
/// above 65535), or "" if it can. launch() refuses such a fleet with this text.
std::string domain_problem(int domain, int agents);

/// Short human summary of a summary.json.
std::string human_summary(const nlohmann::json& s);

}  // namespace maptr::deploy
