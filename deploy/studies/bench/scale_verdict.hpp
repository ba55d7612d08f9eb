#pragma once
// The answer of `maptr bench scale` for one fleet size and mode: did the fleet end ok, and did
// it meet the thresholds given (--min-rtf, --max-floor-ratio)? Pure: unit-tested.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace maptr::deploy {

struct ScaleThresholds {
  double min_rtf = -1;          ///< real-time factor at least this (-1: not checked)
  double max_floor_ratio = -1;  ///< median tick at most this many times the IPC floor's (-1: not checked)
};

/// Why a row of scale.csv misses (empty: it passes): its status, and each threshold it misses
/// with the figure and the bound ("RTF 95.2 < --min-rtf 1000").
std::vector<std::string> scale_misses(const nlohmann::json& row, const ScaleThresholds& t);

/// The headline of a row: "N=16 ec, 1 host: ok, RTF 95.2, tick 1.20 ms = 2.6 x floor, discovery 1.6 s"
/// followed by PASS or MISS and the reasons.
std::string scale_headline(const nlohmann::json& row, const std::vector<std::string>& misses);

}  // namespace maptr::deploy
