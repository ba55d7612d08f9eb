#include "records/run_files.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace maptr::records {

std::string summary_path(const std::string& run_dir) { return run_dir + "/summary.json"; }
std::string plant_results_path(const std::string& run_dir) { return run_dir + "/plant.json"; }
std::string fleet_file_path(const std::string& run_dir) { return run_dir + "/fleet.json"; }
std::string trace_path(const std::string& run_dir) { return run_dir + "/trace.csv"; }
std::string assignments_path(const std::string& run_dir) { return run_dir + "/assignments.csv"; }
std::string mcap_path(const std::string& run_dir) { return run_dir + "/run.mcap"; }

void write_json_file(const std::string& path, const nlohmann::json& j) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << j.dump(2) << "\n";
    if (!out) throw std::runtime_error("cannot write " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

nlohmann::json read_json_object(const std::string& path) {
  std::ifstream in(path);
  if (!in) return nlohmann::json::object();
  // Parsed apart, without exceptions: a file cut short reads as nothing, not as the part of an
  // object before the cut.
  nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  return j.is_object() ? j : nlohmann::json::object();
}

}  // namespace maptr::records
