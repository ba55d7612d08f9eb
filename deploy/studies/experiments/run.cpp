#include "deploy/studies/experiments/run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "records/assignments.hpp"
#include "records/result_table.hpp"
#include "records/run_files.hpp"
#include "records/study_columns.hpp"
#include "records/trace.hpp"

namespace maptr::deploy {

using nlohmann::json;
using records::TraceRow;

std::string Run::status() const { return summary.has_status() ? summary.status() : "aborted: no summary"; }

bool Run::aborted() const { return status().rfind("aborted", 0) == 0; }

double Run::energy_kJ() const { return aborted() ? kNaN : summary.energy_J() / 1000.0; }

double Run::mileage() const { return aborted() ? kNaN : summary.mileage_m_per_J(); }

int Run::active_end() const {
  if (aborted() || summary.active_agents("L") < 0) return -1;
  return summary.active_agents("L") + summary.active_agents("R");
}

int Run::active_side(const char* side) const { return aborted() ? -1 : summary.active_agents(side); }

json Run::level2() const {
  json o = {{"decisions", 0}, {"checked", 0}, {"differs", 0}};
  std::vector<double> med;
  for (const auto& s : summary.level2()) {
    o["decisions"] = o["decisions"].get<int>() + s.decisions;
    o["checked"] = o["checked"].get<int>() + s.oracle_checked;
    o["differs"] = o["differs"].get<int>() + s.oracle_differs;
    if (s.solve_ms_median >= 0) med.push_back(s.solve_ms_median);
  }
  if (!med.empty()) o["solve_ms_median"] = med.size() == 2 ? 0.5 * (med[0] + med[1]) : med[0];
  return o;
}

bool Run::speed_held() const {
  const TraceFigures& t = trace;
  return std::isfinite(t.v_end_mps) && std::isfinite(t.ref_end_mps) && t.ref_end_mps > 0 &&
         t.v_end_mps >= (1.0 - plant_core::kSpeedBandPct / 100.0) * t.ref_end_mps;
}

namespace {

/// The trace of a run; empty (with a message when it exists but cannot be read) otherwise.
std::vector<TraceRow> trace_of(const Run& r) {
  const std::string path = records::trace_path(r.dir);
  if (!std::ifstream(path).good()) return {};
  try {
    return records::read_trace(path);
  } catch (const records::RecordError& e) {
    std::fprintf(stderr, "maptr: %s: %s\n", r.dir.c_str(), e.what());
    return {};
  }
}

/// Mean applied voltage of the two sides (both must drive).
double applied_V(const TraceRow& x) { return 0.5 * (x.V_L_mean_V + x.V_R_mean_V); }

/// Efficiency, active agents and applied voltage over the second half of the run.
void second_half(const std::vector<TraceRow>& t, TraceFigures& f) {
  double se = 0, sa = 0, sr = 0, sva = 0;
  int ne = 0, na = 0, nr = 0;
  for (std::size_t i = t.size() / 2; i < t.size(); ++i) {
    const TraceRow& x = t[i];
    sa += x.n_active_L + x.n_active_R;
    ++na;
    if (!(x.n_active_L > 0 && x.n_active_R > 0)) continue;
    se += 0.5 * (x.eff_L + x.eff_R);
    ++ne;
    if (x.battery_V_L > 0 && x.battery_V_R > 0) {
      sr += 0.5 * (x.V_L_mean_V / x.battery_V_L + x.V_R_mean_V / x.battery_V_R);
      sva += applied_V(x);
      ++nr;
    }
  }
  if (ne) f.eff_cruise = se / ne;
  if (na) f.active_cruise = sa / na;
  if (nr) {
    f.v_over_vb = sr / nr;
    f.v_applied = sva / nr;
  }
}

}  // namespace

void derive(Run& r) {
  const auto t = trace_of(r);
  if (t.empty()) return;
  const double rad = r.s.robot.wheel_radius_m;
  for (const auto& x : t) {
    const double ref = x.ref_speed_mps(rad);
    if (ref > 0 && std::fabs(x.v_x_mps - ref) < plant_core::kSpeedBandPct / 100.0 * ref) {
      r.trace.t_reach_s = x.t_s;
      break;
    }
  }
  const std::size_t n = t.size(), tail = std::max<std::size_t>(1, n / 10);
  double sv = 0;
  for (std::size_t i = n - tail; i < n; ++i) sv += t[i].v_x_mps;
  r.trace.v_end_mps = sv / tail;
  r.trace.ref_end_mps = t.back().ref_speed_mps(rad);
  second_half(t, r.trace);
}

double energy_at(const Run& r, double t) {
  double e = kNaN;
  for (const auto& x : trace_of(r))
    if (x.t_s <= t + 1e-9) e = x.energy_J;
  return e;
}

double max_speed_error_after(const Run& r, double t0) {
  const double rad = r.s.robot.wheel_radius_m;
  double m = kNaN;
  for (const auto& x : trace_of(r)) {
    const double ref = x.ref_speed_mps(rad);
    if (x.t_s < t0 || !(ref > 0)) continue;
    const double e = 100.0 * std::fabs(x.v_x_mps - ref) / ref;
    m = std::isfinite(m) ? std::max(m, e) : e;
  }
  return m;
}

namespace {

long long bin_of(double t, double bin_s) {
  constexpr double kEdge = 1e-9;  // a time on a bin's edge starts that bin
  return static_cast<long long>(std::floor(t / bin_s + kEdge));
}

/// One row of the series: the means of rows [first, end) (the last row for the running sums);
/// the applied voltage is absent when no bin row had agents driving on both sides.
json series_row(const std::vector<TraceRow>& t, std::size_t first, std::size_t end, double rad) {
  double st = 0, sv = 0, sref = 0, seff = 0, sn = 0, sb = 0, sva = 0;
  int kv = 0;
  for (std::size_t i = first; i < end; ++i) {
    const TraceRow& x = t[i];
    st += x.t_s;
    sv += x.v_x_mps;
    sref += x.ref_speed_mps(rad);
    seff += 0.5 * (x.eff_L + x.eff_R);
    sn += x.n_active_L + x.n_active_R;
    sb += 0.5 * (x.battery_V_L + x.battery_V_R);
    if (x.n_active_L > 0 && x.n_active_R > 0) {
      sva += applied_V(x);
      ++kv;
    }
  }
  const double k = static_cast<double>(end - first);
  const TraceRow& last = t[end - 1];
  return {{"t_s", st / k},
          {"v_x_mps", sv / k},
          {"ref_mps", sref / k},
          {"eff_agent", seff / k},
          {"n_active", sn / k},
          {"battery_V", sb / k},
          {"V_applied_V", kv ? json(sva / kv) : json(nullptr)},
          {"discharge_mAh", 0.5 * (last.discharge_L_mAh + last.discharge_R_mAh)},
          {"energy_kJ", last.energy_J / 1000.0},
          {"distance_m", last.distance_m}};
}

}  // namespace

void write_series(const Run& r, const std::string& path, double bin_s) {
  const auto t = trace_of(r);
  records::ResultTable series;
  series.cols = records::columns::run_series();
  std::size_t i = 0;
  while (i < t.size()) {
    const long long bin = bin_of(t[i].t_s, bin_s);
    std::size_t end = i;
    while (end < t.size() && bin_of(t[end].t_s, bin_s) == bin) ++end;
    series.rows.push_back(series_row(t, i, end, r.s.robot.wheel_radius_m));
    i = end;
  }
  series.write_csv(path);
}

std::vector<std::vector<Interval>> driving_intervals(const std::string& path, int per_side, double t_end) {
  std::vector<std::vector<Interval>> out(2 * per_side);
  std::vector<records::AssignmentRecord> changes[2];
  for (auto& a : records::read_assignments(path)) changes[a.side == 'L' ? 0 : 1].push_back(std::move(a));
  for (int s = 0; s < 2; ++s)
    for (std::size_t i = 0; i < changes[s].size(); ++i) {
      const double t0 = changes[s][i].t_s, t1 = i + 1 < changes[s].size() ? changes[s][i + 1].t_s : t_end;
      const std::string& m = changes[s][i].driving;
      for (int j = 0; j < per_side && j < static_cast<int>(m.size()); ++j)
        if (m[j] == '1' && t1 > t0) out[s * per_side + j].push_back({t0, t1});
    }
  return out;
}

DrivingOrder driving_first(const Run& r, double at, int per_side) {
  const auto iv = driving_intervals(records::assignments_path(r.dir), per_side, r.sim_s());
  DrivingOrder order;
  for (int side = 0; side < 2; ++side) {
    std::vector<int> on, off;
    for (int j = 0; j < per_side; ++j) {
      const auto& a = iv[static_cast<std::size_t>(side * per_side + j)];
      const bool driving =
          std::any_of(a.begin(), a.end(), [&](const Interval& x) { return x.t0 <= at && at < x.t1; });
      (driving ? on : off).push_back(j);
    }
    order[static_cast<std::size_t>(side)] = on;
    order[static_cast<std::size_t>(side)].insert(order[static_cast<std::size_t>(side)].end(), off.begin(),
                                                 off.end());
  }
  return order;
}

}  // namespace maptr::deploy
