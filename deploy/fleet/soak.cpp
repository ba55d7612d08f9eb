#include "deploy/fleet/soak.hpp"

#include <cmath>
#include <sstream>

#include "deploy/fleet/fault_schedule.hpp"
#include "records/ledger_file.hpp"

namespace maptr::deploy::soak {

namespace {
/// Share of a fleet's outages that are pauses.
constexpr double kPauseShare = 1.0 / 3.0;

std::string pct(double v) {
  std::ostringstream os;
  os.precision(3);
  os << v << "%";
  return os.str();
}
}  // namespace

unsigned fleet_seed(unsigned seed, int index) {
  // splitmix-style mixing: neighbouring seeds and indices give unrelated schedules.
  uint64_t z = (static_cast<uint64_t>(seed) << 32) + static_cast<uint64_t>(index) + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return static_cast<unsigned>((z ^ (z >> 31)) & 0xffffffffu);
}

std::vector<config::FaultSpec> fleet_faults(unsigned seed, int index, const config::Scenario& s,
                                            int outages) {
  ChaosOptions o;
  o.outages = outages;
  o.pause_share = kPauseShare;
  o.discovery = true;
  return chaos_schedule(fleet_seed(seed, index), s, o);
}

std::map<std::string, int> faults_by_kind(const nlohmann::json& summary) {
  std::map<std::string, int> n = {{"kill", 0}, {"restart", 0}, {"pause", 0}, {"resume", 0}, {"skipped", 0}};
  for (const auto& f : summary.value("failures", nlohmann::json::array()))
    ++n[f.contains("skipped") ? std::string("skipped") : f.value("action", "")];
  return n;
}

Deadline fleet_deadline(double elapsed_s, double timeout_s, double grace_s) {
  if (elapsed_s > timeout_s + grace_s) return Deadline::kKill;
  if (elapsed_s > timeout_s) return Deadline::kTerm;
  return Deadline::kNone;
}

std::string check_status(const nlohmann::json& summary) {
  if (!summary.contains("status")) return "no status: summary.json is missing or unreadable";
  const std::string st = summary.value("status", "");
  if (st == "ok") return "";
  const std::string degraded = "degraded: ";
  if (st.rfind(degraded, 0) == 0 && st.size() > degraded.size()) return "";
  return "status '" + st + "' is neither ok nor degraded with a reason";
}

std::vector<std::string> check_wear(const nlohmann::json& summary, const std::string& run_dir, int per_side) {
  std::vector<std::string> out;
  const nlohmann::json wear =
      summary.value("plant", nlohmann::json::object()).value("group_wear", nlohmann::json());
  for (const std::string side : {"L", "R"}) {
    const nlohmann::json seen = wear.is_object() ? wear.value(side, nlohmann::json()) : nlohmann::json();
    if (!seen.is_object()) {
      out.push_back("group-" + side + ": the plant reported no wear ledger");
      continue;
    }
    if (seen.value("regressions", 0) > 0)
      out.push_back("group-" + side + ": the wear ledger went backwards " +
                    std::to_string(seen.value("regressions", 0)) + " times (largest drop " +
                    std::to_string(seen.value("largest_drop_m", 0.0)) + " m)");
    const std::string path = records::ledger_path(run_dir, side == "L" ? 0 : 1);
    std::vector<double> kept;
    try {
      const auto file = records::load_ledger(path);
      if (!file) throw std::runtime_error("missing");
      kept = file->wear_m;
    } catch (const std::exception& e) {
      out.push_back("group-" + side + ": ledger " + path + " lost (" + e.what() + ")");
      continue;
    }
    const auto last = seen.value("wear_m", std::vector<double>{});
    if (static_cast<int>(kept.size()) != per_side) {
      out.push_back("group-" + side + ": ledger has " + std::to_string(kept.size()) + " agents, not " +
                    std::to_string(per_side));
      continue;
    }
    for (std::size_t j = 0; j < std::min(kept.size(), last.size()); ++j)
      if (!std::isfinite(kept[j]) || kept[j] < last[j] - kLedgerToleranceM)
        out.push_back("group-" + side + ": agent " + std::to_string(j) + "'s wear " +
                      std::to_string(kept[j]) + " m in the ledger file is below the " +
                      std::to_string(last[j]) + " m the plant last saw");
  }
  return out;
}

double deviation_pct(double value, double reference) {
  return reference != 0.0 ? 100.0 * (value - reference) / std::fabs(reference) : 0.0;
}

std::vector<std::string> check_detection(const nlohmann::json& summary) {
  std::vector<std::string> out;
  const auto plant = summary.value("plant", nlohmann::json::object());
  for (const auto& d : plant.value("agent_faults", nlohmann::json::object()).value("diagnoses", nlohmann::json::array()))
    if (d.value("false_detection", false))
      out.push_back(d.value("target", "") + " isolated as " + d.value("diagnosed", "") + " at " +
                    std::to_string(d.value("t_s", 0.0)) + " s with no fault in force");
  return out;
}

std::vector<std::string> check_band(const nlohmann::json& summary, const nlohmann::json& reference,
                                    const Band& b) {
  std::vector<std::string> out;
  const double dd = deviation_pct(summary.value("distance_m", 0.0), reference.value("distance_m", 0.0));
  const double de = deviation_pct(summary.value("energy_J", 0.0), reference.value("energy_J", 0.0));
  if (dd < -b.distance_below_pct || dd > b.distance_above_pct)
    out.push_back("distance " + pct(dd) + " off the fault-free run, outside [-" + pct(b.distance_below_pct) +
                  ", +" + pct(b.distance_above_pct) + "]");
  if (std::fabs(de) > b.energy_pct)
    out.push_back("energy " + pct(de) + " off the fault-free run, outside +-" + pct(b.energy_pct));
  return out;
}

}  // namespace maptr::deploy::soak
