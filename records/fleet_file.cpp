#include "records/fleet_file.hpp"

#include <stdexcept>

#include "records/run_files.hpp"

namespace maptr::records {

void to_json(nlohmann::json& j, const FleetProcessEntry& p) {
  j = {{"name", p.name}, {"pid", p.pid}, {"external", p.external}, {"participant_id", p.participant_id}};
  if (p.host) j["host"] = *p.host;
  if (p.host_pid) j["host_pid"] = *p.host_pid;
}

void from_json(const nlohmann::json& j, FleetProcessEntry& p) {
  p.name = j.at("name").get<std::string>();
  p.pid = j.at("pid").get<long>();
  p.external = j.value("external", false);
  p.participant_id = j.value("participant_id", 0);
  p.host = j.value("host", nlohmann::json()).is_null() ? std::nullopt
                                                       : std::optional(j["host"].get<std::string>());
  p.host_pid = j.value("host_pid", nlohmann::json()).is_number() ? std::optional(j["host_pid"].get<long>())
                                                                 : std::nullopt;
}

void write_fleet_file(const std::string& run_dir, const FleetFile& f) {
  write_json_file(fleet_file_path(run_dir), nlohmann::json(f));
}

std::optional<FleetFile> read_fleet_file(const std::string& run_dir) {
  const nlohmann::json j = read_json_object(fleet_file_path(run_dir));
  if (j.empty()) return std::nullopt;
  try {
    return j.get<FleetFile>();
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

FleetFile require_fleet_file(const std::string& run_dir) {
  const std::string path = fleet_file_path(run_dir);
  const nlohmann::json j = read_json_object(path);
  if (j.empty())
    throw std::runtime_error(path + ": no such file (not a run folder, or the fleet has not started)");
  for (const char* key : {"domain", "lease_s", "fleet_id", "launcher_pid", "config"})
    if (!j.contains(key)) throw std::runtime_error(path + ": no " + key);
  try {
    return j.get<FleetFile>();
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace maptr::records
