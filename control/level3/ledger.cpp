#include "control/level3/ledger.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace maptr::control {

Ledger::Ledger(int per_side) : wear_m(per_side, 0.0), active_time_s(per_side, 0.0), assignment(per_side, 0) {}

void Ledger::accrue(const std::vector<uint8_t>& active, double distance_m, double dt_s) {
  for (std::size_t j = 0; j < wear_m.size(); ++j) {
    if (j < active.size() && active[j]) {
      wear_m[j] += distance_m;
      active_time_s[j] += dt_s;
    } else {
      active_time_s[j] = 0.0;
    }
  }
}

bool Ledger::load(const std::string& path, int per_side) {
  std::ifstream in(path);
  if (!in) return false;
  nlohmann::json j;
  try {
    in >> j;
    wear_m = j.at("wear_m").get<std::vector<double>>();
    active_time_s = j.at("active_time_s").get<std::vector<double>>();
    assignment = j.at("assignment").get<std::vector<uint8_t>>();
    last_t = j.at("last_t").get<double>();
    last_alloc_t = j.at("last_alloc_t").get<double>();
    n_target = j.at("n_target").get<int>();
    decisions = j.at("decisions").get<uint64_t>();
    reallocations = j.at("reallocations").get<uint64_t>();
  } catch (const std::exception& e) {
    throw std::runtime_error("wear ledger " + path + " is corrupt: " + e.what());
  }
  if (static_cast<int>(wear_m.size()) != per_side || static_cast<int>(active_time_s.size()) != per_side)
    throw std::runtime_error("wear ledger " + path + " has " + std::to_string(wear_m.size()) +
                             " agents, the scenario " + std::to_string(per_side));
  if (static_cast<int>(assignment.size()) != per_side) assignment.assign(per_side, 0);
  return true;
}

void Ledger::save(const std::string& path) const {
  nlohmann::json j;
  j["wear_m"] = wear_m;
  j["active_time_s"] = active_time_s;
  j["assignment"] = assignment;
  j["last_t"] = last_t;
  j["last_alloc_t"] = last_alloc_t;
  j["n_target"] = n_target;
  j["decisions"] = decisions;
  j["reallocations"] = reallocations;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error("cannot write wear ledger " + tmp);
    out << j.dump(1) << "\n";
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace maptr::control
