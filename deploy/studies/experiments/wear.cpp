// wear: Level-3 task allocation: which agents drive in every T_ON step, idle time, wear.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "deploy/studies/experiments/experiment_list.hpp"
#include "records/ledger_file.hpp"
#include "records/run_files.hpp"
#include "records/study_columns.hpp"

namespace maptr::deploy {

namespace {

struct Conditions {
  std::vector<int> ns;
  double t_on, duration, speed = 10.0, gross = 13.2;
};

Conditions conditions(bool q) {
  if (q) return {{8, 16}, 5.0, 30.0};
  return {{8, 16, 32}, 100.0, 1800.0};
}

/// After the speed first comes within the band: the first Level-2 decision is in, s.
constexpr double kCruiseAfterReachS = 2.0;

/// Idle time per agent: run time minus the plant's driving time of the agent.
void add_idle(json& row, const Run& r, double t_on) {
  std::vector<double> idle;
  for (const char* side : {"L", "R"})
    for (double a : r.summary.agent_active_s(side)) idle.push_back(r.sim_s() - a);
  if (idle.empty()) return;
  double sum = 0;
  for (double v : idle) sum += v;
  row["idle_mean_s"] = sum / idle.size();
  row["idle_mean_steps"] = sum / idle.size() / t_on;
  row["idle_min_steps"] = *std::min_element(idle.begin(), idle.end()) / t_on;
  row["idle_max_steps"] = *std::max_element(idle.begin(), idle.end()) / t_on;
}

/// The wear of every agent of a side from its group controller's ledger (empty when absent).
std::vector<double> ledger_wear(const std::string& path) {
  try {
    const auto ledger = records::load_ledger(path);
    return ledger ? ledger->wear_m : std::vector<double>{};
  } catch (const std::exception&) {
    return {};
  }
}

void add_wear(json& row, const Run& r) {
  double wmin = 1e300, wmax = -1e300;
  for (int side = 0; side < 2; ++side) {
    const auto w = ledger_wear(records::ledger_path(r.dir, side));
    if (w.empty()) continue;
    const auto [lo, hi] = std::minmax_element(w.begin(), w.end());
    row[side ? "wear_spread_R_m" : "wear_spread_L_m"] = *hi - *lo;
    row[side ? "wear_R_m" : "wear_L_m"] = w;
    wmin = std::min(wmin, *lo);
    wmax = std::max(wmax, *hi);
  }
  if (wmax >= wmin) {
    row["wear_min_m"] = wmin;
    row["wear_max_m"] = wmax;
  }
}

/// Writes transitions-N<n>.csv (driving fraction of every agent in every T_ON step) and plots it.
void transitions(Experiment& e, int n, double t_on, double T, const std::vector<std::vector<Interval>>& iv) {
  const int per_side = n / 2;
  const int steps = static_cast<int>(std::ceil(T / t_on - 1e-9));
  records::ResultTable tr;
  tr.cols = {{"step", "step", 0},
             {"t_start_s", "start (s)", 1},
             {"agent", "agent", 0},
             {"name", "name", -1},
             {"driving_fraction", "driving", 4}};
  for (int a = 0; a < n; ++a)  // gnuplot's "with image" wants x (the step) to vary fastest
    for (int k = 0; k < steps; ++k) {
      const double s0 = k * t_on, s1 = std::min(T, (k + 1) * t_on);
      double on = 0;
      for (const auto& x : iv[a]) on += std::max(0.0, std::min(x.t1, s1) - std::max(x.t0, s0));
      tr.rows.push_back({{"step", k},
                         {"t_start_s", s0},
                         {"agent", a},
                         {"name", config::agent_name(a / per_side, a % per_side)},
                         {"driving_fraction", s1 > s0 ? on / (s1 - s0) : 0.0}});
    }
  tr.write_csv(e.dir() + "/transitions-N" + std::to_string(n) + ".csv");
  std::ostringstream yt;
  for (int a = 0; a < n; ++a)
    yt << (a ? ", " : "") << "\"" << config::agent_name(a / per_side, a % per_side) << "\" " << a;
  const std::string ns = std::to_string(n), ton = fixed(t_on, 0);
  e.plot("wear-transitions-N" + ns,
         "set title 'Which agents drive, EC, N = " + ns + " (1 step = T_ON = " + ton +
             " s)'\nset xlabel 'step (T_ON = " + ton + " s)'\nset ylabel 'agent'\nset ytics (" + yt.str() +
             ") font ',8'\nset cblabel 'fraction of the step spent driving'\nset cbrange [0:1]\n"
             "set palette defined (0 'white', 1 'dark-blue')\nset xrange [-0.5:" +
             fixed(steps - 0.5, 1) + "]\nset yrange [-0.5:" + fixed(n - 0.5, 1) +
             "]\nunset grid\nset key off\n"
             // Columns by number: gnuplot 5.4 draws nothing "with image" when they are named.
             "plot 'transitions-N" +
             ns + ".csv' using 1:3:5 with image\n");
}

/// Agents that drove once the robot cruised: more than N_a of them means Level 3 rotated the work.
void add_drove_in_cruise(json& row, const Run& r, int per_side,
                         const std::vector<std::vector<Interval>>& iv) {
  const double cruise_t = (std::isfinite(r.trace.t_reach_s) ? r.trace.t_reach_s : 0.0) + kCruiseAfterReachS;
  for (int side = 0; side < 2; ++side) {
    int drove = 0;
    for (int j = 0; j < per_side; ++j)
      if (std::any_of(iv[side * per_side + j].begin(), iv[side * per_side + j].end(),
                      [&](const Interval& x) { return x.t1 > cruise_t; }))
        ++drove;
    row[side ? "drove_in_cruise_R" : "drove_in_cruise_L"] = drove;
  }
}

json row_of(Experiment& e, const Conditions& c, int n, const Run& r) {
  json row = {{"agents", n}, {"status", r.status()}, {"t_on_s", c.t_on}};
  if (r.aborted()) return row;
  add_idle(row, r, c.t_on);
  add_wear(row, r);
  // Greedy least-worn allocation at most T_ON apart: no agent gets more than one period's
  // driving ahead of the least worn (see docs/results/RESULTS.md).
  row["spread_bound_m"] = c.speed * c.t_on;
  row["active_mean"] = num(r.trace.active_cruise);
  row["active_end"] = r.active_end();
  row["active_end_L"] = r.active_side("L");
  row["active_end_R"] = r.active_side("R");
  const auto iv = driving_intervals(records::assignments_path(r.dir), n / 2, r.sim_s());
  transitions(e, n, c.t_on, r.sim_s(), iv);
  add_drove_in_cruise(row, r, n / 2, iv);
  return row;
}

std::string intro(const Conditions& c) {
  std::ostringstream o;
  o << "EC, gross mass " << c.gross << " kg, Type-I motors, straight line at " << c.speed << " m/s for "
    << c.duration << " s simulated, T_ON = " << c.t_on
    << " s. Idle time per agent: run time minus the time the agent drove (plant's ledger), in T_ON steps. "
       "Wear: "
       "distance each agent drove while active (the group controllers' ledgers); spread = max - min within a "
       "side; bound = one T_ON of driving at the reference speed. The transition plots "
       "(wear-transitions-N*.png) "
       "show, per T_ON step, the fraction of the step each agent drove.";
  return o.str();
}

}  // namespace

int exp_wear(Experiment& e) {
  const Conditions c = conditions(e.quick());
  e.set_total(static_cast<int>(c.ns.size()));
  records::ResultTable t;
  t.cols = records::columns::wear();
  for (int n : c.ns) {
    config::Scenario s = e.base();
    s.robot.agents = n;
    s.robot.gross_mass_kg = c.gross;
    s.mode = "ec";
    s.control.t_on_s = c.t_on;
    Experiment::straight(s, c.speed, c.duration);
    s.trace_every = trace_every_for(c.duration);
    const Run r = e.run("N" + std::to_string(n), "N=" + std::to_string(n), s);
    t.rows.push_back(row_of(e, c, n, r));
  }
  e.write(t, intro(c), "");
  e.plot("wear-idle",
         "set title 'Average idle time per agent vs number of agents (EC, " + kg_label(c.gross) + " kg, " +
             fixed(c.duration, 0) +
             " s)'\nset xlabel 'agents N'\n"
             "set ylabel 'idle time per agent (steps of T_ON = " +
             fixed(c.t_on, 0) +
             " s)'\n"
             "set logscale x 2\nset xrange [6:40]\nset yrange [0:*]\n"
             "plot 'wear.csv' using \"agents\":\"idle_mean_steps\":\"idle_min_steps\":\"idle_max_steps\" "
             "with yerrorlines lw 2 pt 7 title 'mean (bars: min and max agent)'\n");
  return e.exit_code();
}

}  // namespace maptr::deploy
