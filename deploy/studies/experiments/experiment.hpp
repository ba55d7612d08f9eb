#pragma once
// The context of one experiment: its output folder, its runs (each a whole fleet, resumed when
// the folder already holds a finished run of the identical scenario), its table and its plots.
//
// An experiment writes, into its output folder:
//   <name>.csv      the experiment's table (one row per point),
//   <name>.md       the same table in markdown, with the conditions and the paper's numbers,
//   summary.json    the table as JSON (what the tests read), the conditions and every run,
//   *.png + *.gp    gnuplot plots made from the CSVs written here (series/*.csv for time series),
//   runs/<variant>/ the fleet's own results for each variant.
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "config/scenario.hpp"
#include "deploy/report/gnuplot.hpp"
#include "deploy/studies/experiments/experiments.hpp"
#include "deploy/studies/experiments/run.hpp"
#include "records/result_table.hpp"

namespace maptr::deploy {

// The studies' cells (records/result_table.hpp): a number at its decimals, a finite number or null.
using json = nlohmann::json;
using records::fixed;
using records::num;

class Experiment {
 public:
  explicit Experiment(const ExperimentOptions& o) : o_(o) {}

  const ExperimentOptions& opt() const { return o_; }
  bool quick() const { return o_.quick; }
  const std::string& dir() const { return o_.out; }
  void set_total(int n) { total_ = n; }
  bool stopped() const { return interrupted_; }
  double tick_hz() const { return o_.tick_hz > 0 ? o_.tick_hz : default_tick_hz(o_.name); }

  /// The default scenario at this experiment's tick rate.
  config::Scenario base() const;

  /// Straight line at `speed` for `duration` (and nothing else on the trajectory).
  static void straight(config::Scenario& s, double speed, double duration);

  /// Runs one variant (or reuses its finished run), derives its trace figures, prints a line.
  Run run(const std::string& id, const std::string& label, config::Scenario s);

  /// Writes <name>.csv, <name>.md and summary.json.
  void write(const records::ResultTable& t, const std::string& md_intro, const std::string& md_after,
             nlohmann::json extra = nlohmann::json::object());

  /// Writes STEM.gp next to STEM.png and runs gnuplot in the output folder.
  bool plot(const std::string& stem, const std::string& body,
            const report::PlotFrame& frame = report::PlotFrame{"900,600", ",11"});
  const std::vector<std::string>& plots() const { return plots_; }

  std::string command() const;
  /// 1 when a run was aborted or broke one of the properties it was checked against.
  int exit_code() const { return any_aborted_ || any_broken_ ? 1 : 0; }

 private:
  bool reusable(const Run& r, const config::Scenario& s) const;
  void launch_with_retry(Run& r, const std::string& head);
  /// Checks a finished run against the properties every experiment run must satisfy
  /// (experiment_properties()); a broken one is printed and fails the experiment.
  void check(Run& r, const std::string& head);
  std::string runs_md() const;
  nlohmann::json runs_json() const;

  const ExperimentOptions& o_;
  int total_ = 0, done_ = 0;
  bool interrupted_ = false, any_aborted_ = false, any_broken_ = false;
  std::vector<Run> runs_;
  std::vector<std::string> plots_;
};

/// The properties (maptr check) every run of an experiment must satisfy: its energy balances
/// and no group isolates a healthy agent; with the groups' fault detection on, every fault the
/// scenario injects is detected within a simulated second.
std::vector<properties::Spec> experiment_properties(const config::Scenario& s);

/// `plot` over series/<id>.csv files (pairs of id and title), y column `ycol` against t_s.
std::string series_plot(const std::vector<std::pair<std::string, std::string>>& files_titles,
                        const std::string& ycol, const std::string& style = "lines lw 2");

/// The gross mass (or any value) without trailing zeros: 13.2, 38, 23.4.
std::string kg_label(double kg);

/// Averaging bin of the time series and trace decimation for a run of this length.
double bin_for(double duration);
int trace_every_for(double duration);

}  // namespace maptr::deploy
