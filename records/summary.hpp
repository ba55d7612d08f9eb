#pragma once
// summary.json: the launcher's record of a run. The keys tools read are named here once, with
// typed accessors; a key that is absent reads as NaN (numbers), -1 (counts) or "" (text).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace maptr::records {

namespace summary_key {
inline constexpr const char* kStatus = "status";
inline constexpr const char* kSimTime = "sim_time_s";
inline constexpr const char* kWallTime = "wall_time_s";
inline constexpr const char* kRealTimeFactor = "real_time_factor";
inline constexpr const char* kDiscovery = "discovery_s";
inline constexpr const char* kTicks = "ticks";
inline constexpr const char* kEnergy = "energy_J";
inline constexpr const char* kMileage = "mileage_m_per_J";
inline constexpr const char* kDistance = "distance_m";
inline constexpr const char* kActiveAgents = "active_agents";
inline constexpr const char* kLevel2 = "level2";
inline constexpr const char* kFailures = "failures";
inline constexpr const char* kPlant = "plant";
inline constexpr const char* kTraceSha = "trace_sha256";
// Inside "level2": {"L": {...}, "R": {...}}.
inline constexpr const char* kDecisions = "decisions";
inline constexpr const char* kOracleChecked = "oracle_checked";
inline constexpr const char* kOracleDiffers = "oracle_differs";
inline constexpr const char* kSolveMsMedian = "solve_ms_median";
// Inside "plant".
inline constexpr const char* kEndReason = "end_reason";
inline constexpr const char* kBatteryV = "battery_V";
inline constexpr const char* kDischarge = "battery_discharge_mAh";
inline constexpr const char* kAgentActive = "agent_active_s";
inline constexpr const char* kFinalSpeed = "final_speed_mps";
inline constexpr const char* kLiveAgents = "live_agents";
inline constexpr const char* kTickTiming = "tick_timing_us";
// Inside every entry of "failures".
inline constexpr const char* kDetected = "detected_s";
inline constexpr const char* kRecovered = "recovered_s";
inline constexpr const char* kDetectWallMs = "detect_wall_ms";
}  // namespace summary_key

/// One side's Level-2 figures ("level2": {"L": ..., "R": ...}).
struct Level2Figures {
  int decisions = 0, oracle_checked = 0, oracle_differs = 0;
  double solve_ms_median = -1;  ///< -1 when the side made no decision
};

/// Quantiles of one part of the plant's tick, µs ("plant": {"tick_timing_us": {PART: ...}}).
struct TickTiming {
  bool present = false;
  double median = 0, p90 = 0, p99 = 0;
  double mean = 0, max = 0;
};

/// One injected failure as the launcher saw it (NaN: did not happen / not measured).
struct FailureFigures {
  double detected_s, recovered_s, detect_wall_ms;
};

/// A summary.json, read-only, through its named keys.
class Summary {
 public:
  Summary() = default;
  explicit Summary(nlohmann::json j) : j_(std::move(j)) {}
  /// The summary in `path`; an empty object when the file is missing or not JSON.
  static Summary read(const std::string& path);

  const nlohmann::json& data() const { return j_; }
  bool has_status() const;
  std::string status() const;                                ///< "" when absent
  double number(const char* key) const;                      ///< a top-level number; NaN when absent
  double number_or(const char* key, double fallback) const;  ///< a top-level number or `fallback`
  double sim_time_s() const { return number(summary_key::kSimTime); }
  double wall_time_s() const { return number(summary_key::kWallTime); }
  double real_time_factor() const { return number(summary_key::kRealTimeFactor); }
  double discovery_s() const { return number(summary_key::kDiscovery); }
  double ticks() const { return number(summary_key::kTicks); }
  double energy_J() const { return number(summary_key::kEnergy); }
  double mileage_m_per_J() const { return number(summary_key::kMileage); }
  double distance_m() const { return number(summary_key::kDistance); }
  /// Active agents of side 'L' or 'R' at the end; -1 when absent.
  int active_agents(const char* side) const;
  /// Level-2 figures of each side present in the summary.
  std::vector<Level2Figures> level2() const;
  std::vector<FailureFigures> failures() const;
  const nlohmann::json& failures_json() const;

  // The plant's part.
  std::string end_reason() const;
  double plant_number(const char* key) const;                  ///< NaN when absent
  double plant_side(const char* key, const char* side) const;  ///< plant[key][side]; NaN when absent
  std::vector<double> agent_active_s(const char* side) const;
  const nlohmann::json& live_agents() const;  ///< null when absent
  TickTiming tick_timing(const std::string& part) const;
  const nlohmann::json& tick_timing_json() const;  ///< {} when absent

 private:
  const nlohmann::json& plant() const;
  nlohmann::json j_ = nlohmann::json::object();
};

}  // namespace maptr::records
