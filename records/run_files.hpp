#pragma once
// The JSON files of a run folder, one path function each, with their reader and writer:
//   summary.json  the launcher's record of the run (keys: records/summary_fields.cpp; read
//                 through records::Summary)
//   plant.json    the plant's results, under `plant` in summary.json (its struct, reader and
//                 writer: records/plant_results.hpp)
//   fleet.json    who is who while the fleet runs: the launcher's and every child's pid, name,
//                 host and participant id (its struct, reader and writer: records/fleet_file.hpp)
// The other files have a header of their own: trace, assignments, level2_log, ledger_file, mcap.
#include <nlohmann/json.hpp>
#include <string>

namespace maptr::records {

std::string summary_path(const std::string& run_dir);
std::string plant_results_path(const std::string& run_dir);
std::string fleet_file_path(const std::string& run_dir);
/// The plant's per-tick trace (records/trace.hpp), its assignment changes (records/assignments.hpp)
/// and the recording of the fleet's messages (records/mcap.hpp).
std::string trace_path(const std::string& run_dir);
std::string assignments_path(const std::string& run_dir);
std::string mcap_path(const std::string& run_dir);

/// Writes `j` (indented, one line at the end) to `path` through a temporary file and a rename,
/// so that a reader never sees half a file; throws std::runtime_error if it cannot be written.
void write_json_file(const std::string& path, const nlohmann::json& j);

/// The JSON object in `path`; an empty object if the file is missing, not JSON or not an object.
nlohmann::json read_json_object(const std::string& path);

}  // namespace maptr::records
