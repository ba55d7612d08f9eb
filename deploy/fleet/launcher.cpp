#include "deploy/fleet/launcher.hpp"

#include <filesystem>
#include <fstream>
#include <memory>

#include "comm/dds/dds.hpp"
#include "comm/posix/shm_files.hpp"
#include "deploy/fleet/children.hpp"
#include "deploy/fleet/config.hpp"
#include "deploy/fleet/fault_schedule.hpp"
#include "deploy/fleet/fleet.hpp"
#include "deploy/report/run_plot.hpp"
#include "records/run_files.hpp"

namespace maptr::deploy {

std::string domain_problem(int domain, int agents) {
  const int last_id = fleet::fleet_participants(agents) - 1;
  if (domain >= 0 && last_id <= comm::rtps_max_participant_id(domain)) return "";
  int highest = domain;
  while (highest > 0 && last_id > comm::rtps_max_participant_id(highest)) --highest;
  return "--domain " + std::to_string(domain) + ": a fleet of " + std::to_string(agents) + " agents has " +
         std::to_string(last_id + 1) + " DDS participants, whose ports would go up to " +
         std::to_string(*comm::rtps_ports(domain, last_id).rbegin()) +
         ", above 65535; use a domain from 0 to " + std::to_string(highest);
}

std::string secure_problem(const LaunchOptions& o) {
  if (!o.secure) return "";
  if (o.scenario.hosts.enabled())
    return "--secure with hosts (--hosts N, hosts.count " + std::to_string(o.scenario.hosts.count) +
           "): a fleet on several hosts finds itself through its hosts' discovery servers, and a secure "
           "fleet has none (simple discovery): run it on one host";
  for (const auto& f : o.scenario.faults)
    if (f.target == fleet::kDiscoveryTarget)
      return "--secure: faults[] target 'discovery': a secure fleet uses simple discovery and has no "
             "discovery server to " +
             f.action;
  const int max_agents = fleet::FleetConfig{}.secure_max_agents;
  if (o.transport == "udp" || o.scenario.robot.agents > max_agents)
    return "--secure: the fleet runs on shared memory (up to " + std::to_string(max_agents) +
           " agents, --transport auto or shm): its simple discovery needs multicast, which the loopback "
           "interface does not carry";
  return "";
}

namespace {

nlohmann::json launch_once(const LaunchOptions& o, spdlog::logger& log) {
  // Set up: the run directory, the fleet's discovery server, the launcher's participant.
  auto fleet = std::make_unique<fleet::Fleet>(o, log);
  auto& f = *fleet;
  // Start the controllers and the first wave of agents; the next waves start as the previous
  // ones become ready, until every process has matched what it needs.
  f.start_processes();
  if (f.discover()) f.start_run();
  // Run until the plant ends: progress, faults at the plant's gates, commands, deaths.
  f.run();
  // End every process, then the discovery server; remove the fleet's shared-memory ports.
  f.end();
  nlohmann::json s = f.summary();
  // A participant whose deletion Fast DDS never finished may still call the fleet's listeners:
  // the fleet stays, and the process ends with _exit (run_command.cpp, isolated_launch.cpp).
  if (comm::participant_left_open()) (void)fleet.release();
  return s;
}

/// The domain of a second attempt: the next one, or the one below when the next cannot hold
/// the fleet's ports.
int retry_domain(int domain, int agents) {
  if (domain_problem(domain + 1, agents).empty()) return domain + 1;
  return domain > 0 ? domain - 1 : domain;
}

/// Keeps the files of a first attempt in RUN/first-attempt/ (its logs and summary). The
/// launcher's own log is copied, not moved: the launcher keeps writing to it, and the second
/// attempt's lines belong in RUN/logs/launcher.log after the first attempt's.
void keep_first_attempt(const std::string& run_dir) {
  namespace fs = std::filesystem;
  const fs::path keep = fs::path(run_dir) / "first-attempt";
  const fs::path logs = fs::path(run_dir) / "logs";
  fs::create_directories(keep / "logs");
  std::error_code ec;
  for (const auto& f : fs::directory_iterator(logs, ec)) {
    std::error_code one;
    if (f.path().filename() == "launcher.log")
      fs::copy_file(f.path(), keep / "logs" / f.path().filename(), fs::copy_options::overwrite_existing, one);
    else
      fs::rename(f.path(), keep / "logs" / f.path().filename(), one);
  }
  for (const char* name : {"summary.json", "fleet.json"})
    if (fs::exists(fs::path(run_dir) / name)) fs::rename(fs::path(run_dir) / name, keep / name, ec);
}

}  // namespace

nlohmann::json launch(const LaunchOptions& o, spdlog::logger& log) {
  comm::bound_participant_deletion(fleet::FleetConfig{}.participant_delete_s);
  nlohmann::json s = launch_once(o, log);
  // A fleet whose processes did not all report ready in time is not a result: one more attempt
  // with a fresh discovery server on another domain (other ports) before the run is aborted.
  const std::string first = s.value("status", "");
  if (first.rfind(kDiscoveryTimeout, 0) == 0 && !fleet::interrupted().load()) {
    LaunchOptions again = o;
    again.domain = retry_domain(o.domain, o.scenario.robot.agents);
    log.warn("{}; running the fleet once more, with a fresh discovery server, on DDS domain {}", first,
             again.domain);
    keep_first_attempt(o.run_dir);
    s = launch_once(again, log);
    s["discovery_retry"] = {{"first_status", first}, {"first_domain", o.domain}, {"domain", again.domain},
                            {"first_attempt", "first-attempt/"}};
    records::write_json_file(records::summary_path(o.run_dir), s);
  }
  // The picture of the run (run.png), from the files just written.
  report::draw_run_plot(o.run_dir);
  return s;
}

}  // namespace maptr::deploy
