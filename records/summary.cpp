#include "records/summary.hpp"

#include <cmath>
#include <limits>

#include "records/run_files.hpp"

namespace maptr::records {

namespace k = summary_key;
using nlohmann::json;

namespace {
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const json& empty_object() {
  static const json e = json::object();
  return e;
}
const json& null_json() {
  static const json n;
  return n;
}
double number_in(const json& j, const char* key) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_number()) return kNaN;
  return j[key].get<double>();
}
}  // namespace

Summary Summary::read(const std::string& path) { return Summary(read_json_object(path)); }

bool Summary::has_status() const {
  return j_.is_object() && j_.contains(k::kStatus) && j_[k::kStatus].is_string();
}

std::string Summary::status() const { return has_status() ? j_[k::kStatus].get<std::string>() : ""; }

double Summary::number(const char* key) const { return number_in(j_, key); }

double Summary::number_or(const char* key, double fallback) const {
  const double v = number_in(j_, key);
  return std::isnan(v) ? fallback : v;
}

int Summary::active_agents(const char* side) const {
  if (!j_.contains(k::kActiveAgents)) return -1;
  return j_[k::kActiveAgents].value(side, 0);
}

std::vector<Level2Figures> Summary::level2() const {
  std::vector<Level2Figures> out;
  if (!j_.contains(k::kLevel2) || !j_[k::kLevel2].is_object()) return out;
  for (const auto& [side, s] : j_[k::kLevel2].items()) {
    Level2Figures f;
    f.decisions = s.value(k::kDecisions, 0);
    f.oracle_checked = s.value(k::kOracleChecked, 0);
    f.oracle_differs = s.value(k::kOracleDiffers, 0);
    if (s.contains(k::kSolveMsMedian)) f.solve_ms_median = s[k::kSolveMsMedian].get<double>();
    out.push_back(f);
  }
  return out;
}

const json& Summary::failures_json() const {
  static const json none = json::array();
  return j_.contains(k::kFailures) && j_[k::kFailures].is_array() ? j_[k::kFailures] : none;
}

std::vector<FailureFigures> Summary::failures() const {
  std::vector<FailureFigures> out;
  for (const auto& f : failures_json())
    out.push_back({number_in(f, k::kDetected), number_in(f, k::kRecovered), number_in(f, k::kDetectWallMs)});
  return out;
}

const json& Summary::plant() const {
  return j_.contains(k::kPlant) && j_[k::kPlant].is_object() ? j_[k::kPlant] : empty_object();
}

std::string Summary::end_reason() const { return plant().value(k::kEndReason, std::string()); }

double Summary::plant_number(const char* key) const { return number_in(plant(), key); }

double Summary::plant_side(const char* key, const char* side) const {
  return plant().contains(key) ? number_in(plant()[key], side) : kNaN;
}

std::vector<double> Summary::agent_active_s(const char* side) const {
  if (!plant().contains(k::kAgentActive) || !plant()[k::kAgentActive].contains(side)) return {};
  return plant()[k::kAgentActive][side].get<std::vector<double>>();
}

const json& Summary::live_agents() const {
  return plant().contains(k::kLiveAgents) ? plant()[k::kLiveAgents] : null_json();
}

const json& Summary::tick_timing_json() const {
  return plant().contains(k::kTickTiming) && plant()[k::kTickTiming].is_object() ? plant()[k::kTickTiming]
                                                                                 : empty_object();
}

TickTiming Summary::tick_timing(const std::string& part) const {
  const json& t = tick_timing_json();
  if (!t.contains(part)) return {};
  const json& q = t[part];
  return {true, q.value("median", 0.0), q.value("p90", 0.0), q.value("p99", 0.0), q.value("mean", 0.0),
          q.value("max", 0.0)};
}

}  // namespace maptr::records
