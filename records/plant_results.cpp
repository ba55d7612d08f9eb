#include "records/plant_results.hpp"

#include <filesystem>

#include "records/csv.hpp"
#include "records/run_files.hpp"

namespace maptr::records {

nlohmann::json to_json(const PlantResults& r) { return nlohmann::json(r); }

PlantResults plant_results_from_json(const nlohmann::json& j, const std::string& what) {
  try {
    return j.get<PlantResults>();
  } catch (const nlohmann::json::exception& e) {
    throw RecordError(what + ": not the plant's results: " + e.what());
  }
}

void write_plant_results(const std::string& run_dir, const PlantResults& r) {
  write_json_file(plant_results_path(run_dir), to_json(r));
}

std::optional<PlantResults> read_plant_results(const std::string& run_dir) {
  const std::string path = plant_results_path(run_dir);
  const nlohmann::json j = read_json_object(path);  // {} when missing, cut short or not an object
  if (j.empty()) return std::nullopt;
  return plant_results_from_json(j, path);
}

}  // namespace maptr::records
