// failures: kill 0, 1, 2, ... agents per side, the driving ones first, and see the speed hold.
#include <algorithm>
#include <sstream>

#include "deploy/studies/experiments/experiment_list.hpp"
#include "plant_core/speed_band.hpp"
#include "records/study_columns.hpp"

namespace maptr::deploy {

namespace {

constexpr int kAgents = 16, kPerSide = kAgents / 2;

struct Conditions {
  double gross = 23.2, speed = 10.0, duration, kill_at;
};

Conditions conditions(bool q) {
  Conditions c;
  c.duration = q ? 30.0 : 60.0;
  c.kill_at = q ? 15.0 : 20.0;
  return c;
}

/// Kill order per side: the agents driving at the kill time in the fault-free run, then the others.
using KillOrder = DrivingOrder;

config::Scenario scenario(const Experiment& e, const Conditions& c, const KillOrder& order, int k) {
  config::Scenario s = e.base();
  s.robot.agents = kAgents;
  s.robot.gross_mass_kg = c.gross;
  s.mode = "ec";
  Experiment::straight(s, c.speed, c.duration);
  s.trace_every = 10;
  for (int side = 0; side < 2; ++side)
    for (int j = 0; j < k; ++j)
      s.faults.push_back(config::FaultSpec::of(config::agent_name(side, order[side][j]), "kill", c.kill_at));
  return s;
}

double max_or(double acc, double v) {
  return std::isfinite(v) ? (std::isfinite(acc) ? std::max(acc, v) : v) : acc;
}

void add_outcome(json& row, const Run& r, const Conditions& c) {
  int detected = 0, recovered = 0;
  double wall_max = kNaN, rec_max = kNaN;
  for (const auto& f : r.summary.failures()) {
    if (std::isfinite(f.detected_s)) ++detected;
    if (std::isfinite(f.recovered_s)) ++recovered;
    rec_max = max_or(rec_max, f.recovered_s);
    wall_max = max_or(wall_max, f.detect_wall_ms);
  }
  row["failures"] = r.summary.failures_json();
  row["detected"] = detected;
  row["recovered"] = recovered;
  row["detect_wall_ms_max"] = num(wall_max);
  row["recovered_s_max"] = num(rec_max);
  // One window for every k (the launcher's per-fault value uses each fault's own).
  row["max_speed_error_pct"] = num(max_speed_error_after(r, c.kill_at));
  row["final_speed_mps"] = num(r.summary.plant_number(records::summary_key::kFinalSpeed));
  row["active_end_L"] = r.active_side("L");
  row["active_end_R"] = r.active_side("R");
  row["energy_kJ"] = num(r.energy_kJ());
  row["eff_cruise"] = num(r.trace.eff_cruise);
  if (!r.summary.live_agents().is_null()) row["live_end"] = r.summary.live_agents();
}

json row_of(const Run& r, int k, int tolerance, const KillOrder& order, const Conditions& c) {
  json row = {{"killed_per_side", k},
              {"tolerance", tolerance >= 0 ? json(tolerance) : json(nullptr)},
              {"status", r.status()}};
  std::string killed;
  for (int side = 0; side < 2; ++side)
    for (int j = 0; j < k; ++j)
      killed += (killed.empty() ? "" : " ") + config::agent_name(side, order[side][j]);
  row["killed"] = killed;
  if (!r.aborted()) add_outcome(row, r, c);
  return row;
}

std::string intro(const Conditions& c) {
  std::ostringstream o;
  o << "EC, 16 agents, gross mass " << c.gross << " kg, straight line at " << c.speed << " m/s for "
    << c.duration << " s simulated. At t = " << c.kill_at
    << " s the launcher SIGKILLs k agents per side: first those driving at that moment in the fault-free run "
       "(the faulty runs repeat it exactly up to the kill), then idle ones by index (column 'killed'). The "
       "tolerance "
       "N_i - N_a,i is read from the fault-free run (k = 0); the "
       "experiment goes up to two kills beyond it (at most every agent of a side). 'max speed error' is the "
       "largest deviation from the reference between the kill time and the end of the run (the same window "
       "for k = "
       "0, where it shows what Level 2 alone does to the speed); 'recovered' counts the kills after which "
       "the speed "
       "came back within "
    << plant_core::kSpeedBandPct << "% of the reference.";
  return o.str();
}

void plots(Experiment& e, const Conditions& c, int tolerance) {
  const std::string tol = std::to_string(tolerance);
  e.plot(
      "failures-speed",
      "set title 'Speed tracking vs killed agents per side (EC, 16 agents, " + kg_label(c.gross) + " kg, " +
          fixed(c.speed, 0) + " m/s)'\nset xlabel 'agents killed per side at t = " + fixed(c.kill_at, 0) +
          " s'\nset ylabel 'max speed error after the kill (%)'\nset y2label 'final speed (m/s)'\n"
          "set ytics nomirror\nset y2tics\nset xtics 1\nset yrange [0:*]\nset y2range [0:" +
          fixed(c.speed * 1.2, 1) + "]\n" +
          (tolerance >= 0
               ? "set arrow from " + tol + ", graph 0 to " + tol +
                     ", graph 1 nohead dt 2\nset label 'tolerance' at " + tol + ", graph 0.95 offset 0.5,0\n"
               : std::string()) +
          report::plot_command(
              {{"failures.csv", "killed_per_side", "max_speed_error_pct", "linespoints lw 2 pt 7",
                "max speed error", "x1y1"},
               {"", "killed_per_side", "final_speed_mps", "linespoints lw 2 pt 5", "final speed", "x1y2"}}));
  e.plot("failures-energy", "set title 'Energy vs killed agents per side (EC, " + fixed(c.duration, 0) +
                                " s)'\nset xlabel 'agents killed per side'\nset ylabel 'energy drawn (kJ)'\n"
                                "set xtics 1\n" +
                                report::plot_command({{"failures.csv", "killed_per_side", "energy_kJ",
                                                       "linespoints lw 2 pt 7", "energy", ""}}));
}

/// Tolerance N_i - N_a,i from the fault-free run (the larger N_a of the two sides); `fallback`
/// when the run does not say.
int tolerance_of(const Run& r, int fallback) {
  const int na = std::max(r.active_side("L"), r.active_side("R"));
  return na >= 0 ? kPerSide - na : fallback;
}

}  // namespace

int exp_failures(Experiment& e) {
  const bool q = e.quick();
  const Conditions c = conditions(q);
  KillOrder order;
  for (int side = 0; side < 2; ++side)
    for (int j = 0; j < kPerSide; ++j) order[side].push_back(j);
  records::ResultTable t;
  t.cols = records::columns::failures();
  std::vector<int> ks = {0};
  int tolerance = -1;
  if (q) ks.push_back(1);
  e.set_total(q ? 2 : 1);
  for (std::size_t i = 0; i < ks.size(); ++i) {
    const int k = ks[i];
    const Run r =
        e.run("kill-" + std::to_string(k), std::to_string(k) + " killed per side", scenario(e, c, order, k));
    if (k == 0 && !r.aborted()) order = driving_first(r, c.kill_at, kPerSide);
    if (k == 0) tolerance = tolerance_of(r, q ? -1 : kPerSide - 1);
    if (k == 0 && !q) {  // up to two kills beyond the tolerance, at most every agent of a side
      const int kmax = std::min(kPerSide, tolerance + 2);
      for (int kk = 1; kk <= kmax; ++kk) ks.push_back(kk);
      e.set_total(1 + kmax);
    }
    t.rows.push_back(row_of(r, k, tolerance, order, c));
  }
  e.write(t, intro(c), "", {{"tolerance", tolerance >= 0 ? json(tolerance) : json(nullptr)}});
  plots(e, c, tolerance);
  return e.exit_code();
}

}  // namespace maptr::deploy
