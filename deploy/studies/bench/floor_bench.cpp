// `maptr bench floor`: the IPC floor of each fleet size (W = N + 3 processes) with a working
// set per worker process (--touch-kb), to isolate what a larger fleet costs each of its
// processes: once W times the memory one process touches per round exceeds the last-level
// cache, every round starts from memory another process evicted.
#include <filesystem>
#include <iostream>

#include "deploy/report/gnuplot.hpp"
#include "deploy/studies/bench/bench_parts.hpp"
#include "deploy/studies/bench/floor.hpp"
#include "records/result_table.hpp"
#include "records/study_columns.hpp"

namespace maptr::deploy {

namespace {

using json = nlohmann::json;
/// Processes besides the agents that answer every tick: 2 groups and central.
constexpr int kAnswersBesideAgents = 3;
constexpr long kRounds = 2000, kWarmup = 200;

std::string floor_plot_body(const std::vector<int>& touch_kb) {
  std::string cmd =
      "set multiplot layout 1,2 title 'IPC floor with a working set per process (pipes, no DDS)'\n"
      "set logscale x 2\nset grid\nset xlabel 'processes W = N + 3'\nset key top left\n"
      "set ylabel 'CPU µs per worker and round'\nset title 'CPU per worker and round'\nplot ";
  std::string tick = "set ylabel 'µs'\nset title 'round median'\nset logscale y\nplot ";
  for (std::size_t i = 0; i < touch_kb.size(); ++i) {
    const std::string sel = "(column(\"touch_kb\") == " + std::to_string(touch_kb[i]) + " ? ";
    const std::string title = " with linespoints title '" + std::to_string(touch_kb[i]) + " KiB'";
    cmd += std::string(i ? ", " : "") + "'floor.csv' using \"workers\":" + sel +
           "column(\"cpu_us_per_worker_round\") : NaN)" + title;
    tick += std::string(i ? ", " : "") + "'floor.csv' using \"workers\":" + sel +
            "column(\"median_us\") : NaN)" + title;
  }
  return cmd + "\n" + tick + "\nunset multiplot\n";
}

}  // namespace

int bench_floor(const BenchOptions& o) {
  std::filesystem::create_directories(o.out);
  records::ResultTable t;
  t.cols = records::columns::bench_floor();
  records::ResultTableWriter csv(o.out + "/floor.csv", t.cols);
  for (int kb : o.touch_kb)  // a working set's rows together: its curves are unbroken
    for (int n : o.agents) {
      const int w = n + kAnswersBesideAgents;
      std::cerr << "maptr: bench floor N=" << n << " (" << w << " processes), " << kb << " KiB each ..."
                << std::flush;
      const FloorResult f = measure_floor(w, kRounds, kWarmup, kb);
      const json row = {{"agents", n},
                        {"workers", w},
                        {"touch_kb", kb},
                        {"median_us", f.median_us},
                        {"p99_us", f.p99_us},
                        {"cpu_us_per_round", f.cpu_us_per_round},
                        {"cpu_us_per_worker_round", f.cpu_us_per_round / w},
                        {"cs_per_round", f.ctx_switches_per_round}};
      csv.append(row);
      t.rows.push_back(row);
      std::cerr << " round " << f.median_us << " µs, CPU " << f.cpu_us_per_round / w << " µs per worker\n";
    }
  records::write_text_file(o.out + "/floor.md", t.md());
  report::draw_plot(o.out, "floor", "made by `maptr bench floor`", report::PlotFrame{"1400,600", ""},
                    floor_plot_body(o.touch_kb));
  std::cout << t.md() << "results: " << o.out << "/floor.csv, floor.md, floor.png\n";
  return 0;
}

}  // namespace maptr::deploy
