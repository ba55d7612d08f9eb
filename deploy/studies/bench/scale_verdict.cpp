#include "deploy/studies/bench/scale_verdict.hpp"

#include <cstdio>

namespace maptr::deploy {

namespace {
double number(const nlohmann::json& row, const char* key) {
  return row.contains(key) && row[key].is_number() ? row[key].get<double>() : 0.0;
}
std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), f, v);
  return buf;
}
}  // namespace

std::vector<std::string> scale_misses(const nlohmann::json& row, const ScaleThresholds& t) {
  std::vector<std::string> out;
  const std::string status = row.value("status_full", row.value("status", std::string("?")));
  if (status != "ok") out.push_back("status " + status);
  const double rtf = number(row, "real_time_factor"), ratio = number(row, "x_floor");
  if (t.min_rtf >= 0 && !(rtf >= t.min_rtf))
    out.push_back("RTF " + fmt("%.1f", rtf) + " < --min-rtf " + fmt("%g", t.min_rtf));
  if (t.max_floor_ratio >= 0 && !(ratio > 0 && ratio <= t.max_floor_ratio))
    out.push_back("tick / floor " + fmt("%.1f", ratio) + " > --max-floor-ratio " +
                  fmt("%g", t.max_floor_ratio));
  return out;
}

std::string scale_headline(const nlohmann::json& row, const std::vector<std::string>& misses) {
  const int hosts = row.value("hosts", 1);
  std::string s =
      "N=" + std::to_string(row.value("agents", 0)) + " " + row.value("mode", std::string()) + ", " +
      std::to_string(hosts) + (hosts == 1 ? " host: " : " hosts: ") + row.value("status", std::string("?")) +
      ", RTF " + fmt("%.1f", number(row, "real_time_factor")) + ", tick " +
      fmt("%.2f", number(row, "tick_median_us") / 1000.0) + " ms = " + fmt("%.1f", number(row, "x_floor")) +
      " x floor, discovery " + fmt("%.2f", number(row, "discovery_s")) + " s: ";
  if (misses.empty()) return s + "PASS";
  s += "MISS (";
  for (std::size_t i = 0; i < misses.size(); ++i) s += (i ? "; " : "") + misses[i];
  return s + ")";
}

}  // namespace maptr::deploy
