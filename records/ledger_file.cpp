#include "records/ledger_file.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace maptr::control {
// The file's keys are the ledger's fields, by name (found by argument-dependent lookup).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Ledger, wear_m, active_time_s, assignment, last_t, last_alloc_t, n_target,
                                   decisions, reallocations)
}  // namespace maptr::control

namespace maptr::records {

std::string ledger_path(const std::string& run_dir, int side) {
  return run_dir + "/ledger-" + (side == 0 ? "L" : "R") + ".json";
}

std::optional<control::Ledger> load_ledger(const std::string& path, int per_side) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  control::Ledger l;
  try {
    nlohmann::json j;
    in >> j;
    j.get_to(l);
  } catch (const std::exception& e) {
    throw std::runtime_error("wear ledger " + path + " is corrupt: " + e.what());
  }
  if (l.active_time_s.size() != l.wear_m.size())
    throw std::runtime_error("wear ledger " + path + " is corrupt: " + std::to_string(l.wear_m.size()) +
                             " wear entries, " + std::to_string(l.active_time_s.size()) + " active times");
  if (per_side >= 0 && static_cast<int>(l.wear_m.size()) != per_side)
    throw std::runtime_error("wear ledger " + path + " has " + std::to_string(l.wear_m.size()) +
                             " agents, the scenario " + std::to_string(per_side));
  if (l.assignment.size() != l.wear_m.size()) l.assignment.assign(l.wear_m.size(), 0);
  return l;
}

void save_ledger(const std::string& path, const control::Ledger& l) {
  const nlohmann::json j = l;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error("cannot write wear ledger " + tmp);
    out << j.dump(1) << "\n";
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace maptr::records
