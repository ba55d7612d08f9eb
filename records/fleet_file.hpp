#pragma once
// fleet.json: who is who while a fleet runs, for the tools that watch or join it (`maptr top`,
// the benches, the soak) and for processes started by hand. The launcher writes it when the
// fleet starts and again at every change of its processes. Writer and reader are one field list.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "records/json_optional.hpp"

namespace maptr::records {

struct FleetProcessEntry {
  std::string name;  ///< "plant", "central", "group-L", "L3", ...
  long pid = 0;
  bool external = false;            ///< started by hand, not by the launcher
  int participant_id = 0;           ///< its DDS participant id (comm/dds/fleet_ids.hpp)
  std::optional<std::string> host;  ///< "h1", ... on several hosts (absent from the file otherwise)
  std::optional<long> host_pid;     ///< started over ssh: its pid on its host (`pid` is its ssh client's)
};

struct FleetFile {
  long launcher_pid = 0;
  int domain = 0;
  std::optional<std::string> discovery_server;  ///< its locator; null without one
  std::optional<long> discovery_server_pid;
  int discovery_own = -1;
  bool secure = false;
  std::string security_dir;
  double lease_s = 0.0;
  long long fleet_id = 0;
  std::string config;  ///< the resolved scenario the processes read
  std::string run_dir, bin_dir;
  std::vector<FleetProcessEntry> processes;
};

void to_json(nlohmann::json& j, const FleetProcessEntry& p);
void from_json(const nlohmann::json& j, FleetProcessEntry& p);
// The keys of fleet.json are the members' names (a process's `host` is absent when not set).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(FleetFile, launcher_pid, domain, discovery_server,
                                                discovery_server_pid, discovery_own, secure, security_dir,
                                                lease_s, fleet_id, config, run_dir, bin_dir, processes)

void write_fleet_file(const std::string& run_dir, const FleetFile& f);
/// The fleet of run_dir; nullopt while the launcher has not written it (or it is not JSON).
std::optional<FleetFile> read_fleet_file(const std::string& run_dir);
/// The same for a tool that cannot go on without it: throws std::runtime_error naming the file
/// and what is missing or wrong.
FleetFile require_fleet_file(const std::string& run_dir);

}  // namespace maptr::records
