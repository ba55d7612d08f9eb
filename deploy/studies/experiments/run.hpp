#pragma once
// One fleet run of an experiment and the figures derived from what it wrote (summary.json,
// trace.csv, assignments.csv).
#include <array>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "deploy/fleet/run_properties.hpp"
#include "plant_core/speed_band.hpp"
#include "records/summary.hpp"

namespace maptr::deploy {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Figures of a run's trace.csv (NaN when the trace does not give them).
struct TraceFigures {
  double t_reach_s = kNaN;      ///< first time within plant_core::kSpeedBandPct of the reference speed
  double v_end_mps = kNaN;      ///< mean speed over the last 10% of the run
  double ref_end_mps = kNaN;    ///< reference at the end
  double eff_cruise = kNaN;     ///< mean per-agent efficiency (mean of eff_L, eff_R), second half
  double active_cruise = kNaN;  ///< mean active agents (L + R), second half
  double v_over_vb = kNaN;      ///< applied voltage / battery voltage, second half
  double v_applied = kNaN;      ///< mean applied voltage, second half, V
};

struct Run {
  std::string id, label, dir;
  config::Scenario s;
  records::Summary summary;
  std::string first_attempt;  ///< the status of a first attempt that was retried
  bool reused = false, retried = false;
  TraceFigures trace;
  /// The properties every run of an experiment is checked against (Experiment::check).
  std::vector<properties::Verdict> verdicts;

  std::string status() const;
  bool aborted() const;
  double energy_kJ() const;
  double mileage() const;
  double sim_s() const { return summary.sim_time_s(); }
  int active_end() const;                   ///< L + R at the end; -1 when unknown
  int active_side(const char* side) const;  ///< -1 when unknown
  /// Level-2 figures over both sides: decisions, oracle checks and disagreements, and the mean
  /// of the sides' median Ipopt solve times.
  nlohmann::json level2() const;
  /// The speed stayed within plant_core::kSpeedBandPct of the reference at the end of the run.
  bool speed_held() const;
};

/// Reads RUN_DIR/trace.csv into r.trace (a missing or unreadable trace leaves NaN, with a
/// message when it is unreadable).
void derive(Run& r);

/// Energy drawn up to the last trace row at or before t, J (NaN without a trace).
double energy_at(const Run& r, double t);

/// Largest |v - v_ref| / v_ref in percent over the trace rows with t >= t0.
double max_speed_error_after(const Run& r, double t0);

/// The run's time series averaged over bins of bin_s, written to `path` (for the plots).
void write_series(const Run& r, const std::string& path, double bin_s);

struct Interval {
  double t0, t1;
};

/// Per agent (L0.., then R0..), the intervals during which it drove, from assignments.csv.
std::vector<std::vector<Interval>> driving_intervals(const std::string& path, int per_side, double t_end);

/// Per side, the agents' indices: those driving at time `at` in run r first, then the others
/// (each group by index). A run repeated with faults from `at` on is identical up to then (the
/// lock-step is deterministic): faults on the first k hit driving agents first.
using DrivingOrder = std::array<std::vector<int>, 2>;
DrivingOrder driving_first(const Run& r, double at, int per_side);

}  // namespace maptr::deploy
