#pragma once
// Where a fleet's processes run when it runs on several hosts: the hosts (network namespaces on
// this machine, or the machines of the scenario's hosts block), the state of each (lost, cut
// off), their links, and the host of each process. The fleet asks it where to start a process
// and tells it of host faults; the processes themselves (killing, announcing) stay the fleet's.
#include <spdlog/logger.h>

#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "deploy/fleet/children.hpp"
#include "deploy/fleet/host_files.hpp"
#include "deploy/fleet/hosts.hpp"
#include "deploy/fleet/ssh_servers.hpp"

namespace maptr::deploy::fleet {

/// A controller of a lost host started again on a surviving one (hosts.failover).
struct Failover {
  std::string name;            ///< central, group-L or group-R
  std::string from, to;        ///< hosts; `to` empty while it waits to be reaped, or with no host left
  double detected_at_s = 0.0;  ///< simulated time of the host's loss
  double running_at_s = -1.0;  ///< simulated time it was ready again (-1: not ready by the end)
  double ready_wall_s = -1.0;  ///< wall time from its start on the new host to ready, s
  std::chrono::steady_clock::time_point started;
  std::string problem;  ///< why it was not started again ("" when it was)
};

/// The failovers as the summary lists them (null times when they did not happen).
nlohmann::json failovers_json(const std::vector<Failover>& f);

class HostPlacement {
 public:
  /// The hosts of `hc`: namespace hosts made now (after removing those of runs that no longer
  /// live), or the machines it names. `domain` gives the discovery servers' port. Throws
  /// std::runtime_error when the namespaces cannot be made.
  HostPlacement(const config::HostsConfig& hc, int domain, const std::string& run_dir, spdlog::logger& log);
  ~HostPlacement();  ///< removes the namespaces, veths and bridge
  HostPlacement(const HostPlacement&) = delete;
  HostPlacement& operator=(const HostPlacement&) = delete;

  int count() const { return static_cast<int>(hosts_.size()); }
  const Host& host(int h) const { return hosts_.at(static_cast<std::size_t>(h)); }
  /// Namespace hosts on this machine (their links are the launcher's to cut).
  bool namespaces() const { return net_ != nullptr; }
  /// The address the launcher's participant uses: the bridge's, or the scenario's launcher_address.
  const std::string& launcher_address() const { return launcher_address_; }
  /// Every host's discovery server, comma-separated (each server knows the others).
  std::string discovery_servers() const;

  /// The settings a process on host `h` gets from it: its host, command prefix, UDP interface
  /// and discovery server (its host's own; comm::DdsOptions::own_server says why).
  Child host_template(int h) const;
  /// The first of `binaries` that host h cannot run (checked there, through its command prefix,
  /// in one command), "" when it has them all or starts processes directly.
  std::string missing_binary(int h, const std::vector<std::string>& binaries) const;
  /// Puts each child on its host, by the scenario's placement.
  void place(std::vector<Child>& kids) const;
  /// A child whose host is lost or cut off moves to the next host that is neither (false: it
  /// stays, as no host is left or its own is reachable).
  bool move_off_unreachable(Child& c) const;
  /// Whether a host other than h is neither lost nor cut off.
  bool reachable_besides(int h) const;

  /// kill-host: the host's link is cut and it counts as lost and cut off.
  void lose(int h);
  /// partition: cuts the host's link; false when the bridge did not take the cut.
  bool cut_off(int h);
  /// heal: links the host again; returns whether it had been lost (its discovery server then
  /// starts again).
  bool heal(int h);

  /// Writes the resolved scenario (`scenario_text`, RUN/scenario.yaml) into the run folder of
  /// every host reached over a command prefix that does not share the launcher's disk (after the
  /// launcher's marker file: host_files.hpp). Throws config::ScenarioError naming a host whose
  /// run folder cannot be written.
  void ship(const std::string& scenario_text);
  /// Copies back and merges the run folder of each host with a disk of its own, at the end
  /// (a lost or cut-off host: whatever can still be reached); each host's line is in record().
  void collect();

  /// The hosts' part of the summary: name, address, kind, processes, discovery server and the
  /// bytes on each namespace host's link (`servers`: each host's server locator).
  nlohmann::json record(const std::vector<Child>& kids, const std::vector<std::string>& servers) const;

 private:
  const config::HostsConfig& hc_;
  int domain_;
  spdlog::logger& log_;
  std::unique_ptr<NamespaceNet> net_;
  std::unique_ptr<SshServers> ssh_;  ///< hosts.ssh: a server per namespace host (ended before net_ goes)
  std::vector<Host> hosts_;
  std::string launcher_address_;
  std::string run_dir_;
  std::vector<HostDisk> disks_;     ///< per host, from ship()
  std::vector<std::string> files_;  ///< per host: what collect() did with its run folder
};

}  // namespace maptr::deploy::fleet
