#include "deploy/fleet/run_history.hpp"

#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "config/scenario.hpp"
#include "records/run_files.hpp"
#include "records/trace.hpp"

namespace maptr::deploy::properties {

History load_history(const std::string& dir) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(dir)) throw std::runtime_error(dir + ": not a folder");
  History h;
  h.summary = records::read_json_object(records::summary_path(dir));
  if (h.summary.empty())
    throw std::runtime_error(records::summary_path(dir) + ": missing or not a JSON object (a run that did not end?)");
  h.trace = records::read_trace(records::trace_path(dir));
  h.recording_file = fs::exists(records::mcap_path(dir));
  const std::string scenario = dir + "/scenario.yaml";
  if (fs::exists(scenario)) {
    const auto sc = config::load_scenario(scenario);
    h.record = sc.record;
    h.path_tolerance_m = sc.control.path_tolerance_m;
  }
  return h;
}

std::string repro_yaml(const std::string& scenario_text, const std::vector<std::string>& what_broke,
                       const std::string& trace_sha256) {
  std::ostringstream os;
  os << "# A reproducer: `maptr run` of this file runs the fleet again (the lock-step is deterministic:\n"
     << "# trace_sha256 " << trace_sha256 << ") and breaks again:\n";
  for (const auto& w : what_broke) os << "#   " << w << "\n";
  os << "# `maptr check RUN --property ...` checks a run of it.\n" << scenario_text;
  return os.str();
}

}  // namespace maptr::deploy::properties
