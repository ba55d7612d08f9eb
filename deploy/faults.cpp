#include "deploy/faults.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

namespace maptr::deploy {

std::vector<config::FaultSpec> chaos_schedule(unsigned seed, const config::Scenario& s, int faults) {
  std::mt19937 rng(seed);
  std::vector<std::string> targets = {"group-L", "group-R", "central"};
  for (int side = 0; side < 2; ++side)
    for (int j = 0; j < s.robot.per_side(); ++j) targets.push_back(config::agent_name(side, j));
  // Faults start once the robot is moving and leave time to recover before the end.
  const double t0 = std::min(5.0, 0.2 * s.duration_s), t1 = std::max(t0, s.duration_s - 10.0);
  std::uniform_real_distribution<double> when(t0, t1), back(2.0, 8.0);
  std::uniform_int_distribution<std::size_t> who(0, targets.size() - 1);
  std::vector<config::FaultSpec> out;
  for (int i = 0; i < faults; ++i) {
    const std::string target = targets[who(rng)];
    const double at = std::round(when(rng) * 100.0) / 100.0;
    const double again = std::min(s.duration_s, std::round((at + back(rng)) * 100.0) / 100.0);
    // One outage per target: skip a target that is already scheduled to be down then.
    bool overlaps = false;
    for (std::size_t k = 0; k + 1 < out.size(); k += 2)
      if (out[k].target == target && at <= out[k + 1].at_s + 0.5 && again >= out[k].at_s - 0.5) overlaps = true;
    if (overlaps) continue;
    out.push_back({target, "kill", at});
    out.push_back({target, "restart", again});
  }
  return out;
}

namespace {

struct Row {
  double t, err_pct;
};

std::vector<Row> speed_errors(const std::string& path, double r) {
  std::vector<Row> rows;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<double> c;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');) c.push_back(std::strtod(f.c_str(), nullptr));
    if (c.size() < 11) continue;
    const double ref = 0.5 * (c[9] + c[10]) * r;
    rows.push_back({c[1], ref > 0.0 ? 100.0 * std::fabs(c[5] - ref) / ref : 0.0});
  }
  return rows;
}

}  // namespace

void analyse_faults(nlohmann::json& failures, const nlohmann::json& events, const std::string& trace_csv,
                    double wheel_radius_m, double band_pct) {
  const std::vector<Row> rows = speed_errors(trace_csv, wheel_radius_m);
  const double t_end = rows.empty() ? 0.0 : rows.back().t;
  for (std::size_t i = 0; i < failures.size(); ++i) {
    auto& f = failures[i];
    const double at = f.value("at_s", 0.0);
    const std::string target = f.value("target", "");
    const bool restart = f.value("action", "") == "restart";
    // Detection: the first membership event of the target at or after the fault.
    f["detected_s"] = nullptr;
    f["detect_wall_ms"] = nullptr;
    for (const auto& e : events) {
      if (e.value("name", "") != target || e.value("t_s", -1.0) < at - 1e-9) continue;
      if ((e.value("event", "") == "rejoined") != restart) continue;
      f["detected_s"] = e.value("t_s", 0.0);
      if (f.contains("wall_ms")) f["detect_wall_ms"] = e.value("wall_ms", 0.0) - f.value("wall_ms", 0.0);
      break;
    }
    // Recovery window: until the next fault (or the end of the run).
    double until = t_end + 1.0;
    for (std::size_t k = 0; k < failures.size(); ++k)
      if (k != i && failures[k].value("at_s", 0.0) > at) until = std::min(until, failures[k].value("at_s", 0.0));
    double max_err = 0.0, last_out = -1.0, last_in = -1.0;
    for (const auto& r : rows) {
      if (r.t < at || r.t >= until) continue;
      last_in = r.t;
      max_err = std::max(max_err, r.err_pct);
      if (r.err_pct > band_pct) last_out = r.t;
    }
    const double step = rows.size() > 1 ? rows[1].t - rows[0].t : 0.0;
    f["max_speed_error_pct"] = max_err;
    if (last_in < 0.0 || (last_out >= 0.0 && last_out >= last_in))
      f["recovered_s"] = nullptr;  // no data, or still outside the band when the window closed
    else
      f["recovered_s"] = last_out < 0.0 ? at : last_out + step;  // at: it never left the band
  }
}

}  // namespace maptr::deploy
