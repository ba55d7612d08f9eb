#include "deploy/fleet/launcher.hpp"

#include "comm/shm_files.hpp"
#include "deploy/fleet/children.hpp"
#include "deploy/fleet/config.hpp"
#include "deploy/fleet/fault_schedule.hpp"
#include "deploy/fleet/fleet.hpp"

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
  for (const auto& f : o.scenario.faults)
    if (f.target == fleet::kDiscoveryTarget)
      return "--secure: faults[] target 'discovery': a secure fleet uses simple discovery and has no "
             "discovery "
             "server to " +
             f.action;
  const int max_agents = fleet::FleetConfig{}.shm_max_agents;
  if (o.transport == "udp" || o.scenario.robot.agents > max_agents)
    return "--secure: the fleet runs on shared memory (up to " + std::to_string(max_agents) +
           " agents, --transport auto or shm): its simple discovery needs multicast, which the loopback "
           "interface "
           "does not carry";
  return "";
}

nlohmann::json launch(const LaunchOptions& o, spdlog::logger& log) {
  // Set up: the run directory, the fleet's discovery server, the launcher's participant.
  fleet::Fleet f(o, log);
  // Start the controllers and the first wave of agents; the next waves start as the previous
  // ones become ready, until every process has matched what it needs.
  f.start_processes();
  if (f.discover()) f.start_run();
  // Run until the plant ends: progress, faults at the plant's gates, commands, deaths.
  f.run();
  // End every process, then the discovery server; remove the fleet's shared-memory ports.
  f.end();
  return f.summary();
}

}  // namespace maptr::deploy
