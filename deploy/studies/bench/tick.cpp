// `maptr bench tick`: where the time of one lock-step tick goes (publish, barrier, integrate).
#include <filesystem>
#include <iostream>
#include <sstream>

#include "deploy/fleet/isolated_launch.hpp"
#include "deploy/studies/bench/bench_parts.hpp"
#include "deploy/studies/bench/cost_watch.hpp"
#include "deploy/studies/bench/floor.hpp"
#include "records/result_table.hpp"
#include "records/run_files.hpp"
#include "records/study_columns.hpp"
#include "records/summary.hpp"

namespace maptr::deploy {

namespace {
/// Speed of the tick bench's straight line, m/s.
constexpr double kTickSpeed = 10.0;

std::string timing_md(const records::Summary& sum) {
  records::ResultTable t;
  t.cols = {{"part", "part", -1}, {"median", "median µs", 0}, {"p90", "p90 µs", 0}, {"p99", "p99 µs", 0}};
  const std::pair<const char*, const char*> parts[] = {
      {"publish", "plant publishes PlantTick k (write returns)"},
      {"first_reply", "first agent reply after the write returned"},
      {"barrier", "write returned -> every live agent, group and central answered"},
      {"integrate", "CVODE over [t_k, t_k+1] + trace row"},
      {"tick", "whole tick"}};
  for (const auto& [key, what] : parts) {
    const records::TickTiming tt = sum.tick_timing(key);
    if (!tt.present) continue;
    t.rows.push_back({{"part", std::string(key) + " (" + what + ")"},
                      {"median", tt.median},
                      {"p90", tt.p90},
                      {"p99", tt.p99}});
  }
  return t.md();
}
/// Context switches and CPU per tick by process kind, over the measured window.
std::string cost_md(const FleetCost& c) {
  if (!c.measured) return "Cost per process kind: not measured (the run ended before its window).\n";
  records::ResultTable t;
  for (const auto& col : records::columns::bench_fleet_cost()) t.cols.push_back(col);
  t.rows.push_back(fleet_cost_json(c));
  return "Cost per tick by process kind, from /proc over a window of " + std::to_string(c.ticks) +
         " ticks (cs: context switches, over all threads):\n\n" + t.md();
}
}  // namespace

int bench_tick(const BenchOptions& o) {
  const int n = o.agents.size() == 1 ? o.agents.front() : 16;
  config::Scenario s = config::load_scenario(o.source_dir + "/deploy/scenarios/paper.yaml");
  s.robot.agents = n;
  s.duration_s = o.duration_s;
  s.trajectory.segments = {config::Segment{"straight", kTickSpeed, 0.0, o.duration_s}};
  s.name = "tick-" + std::to_string(n);
  s.record = o.record;
  s.realtime = o.realtime;
  s.tick_filter = o.tick_filter;
  if (o.plant_priority >= 0) s.plant_priority = o.plant_priority;
  s.validate();
  const std::string run_dir = o.out + "/runs/tick-N" + std::to_string(n);
  FleetCost cost;
  const records::Summary sum(launch_isolated(LaunchOptions::of(s, run_dir, o.bin_dir, o.domain), "",
                                             [&](const std::atomic<bool>& done) {
                                               cost = watch_fleet_cost(run_dir, cost_window(s.ticks()), done);
                                             }));
  const FloorResult floor = measure_floor(n + 3);  // agents, 2 groups and central answer each tick
  const double tick_us = sum.tick_timing("tick").median;
  std::ostringstream md;
  md << "Lock-step tick, N = " << n << ", " << o.duration_s << " s simulated at 100 Hz ("
     << static_cast<long long>(sum.number_or(records::summary_key::kTicks, 0)) << " ticks, run.mcap records "
     << o.record << (o.realtime ? ", paced to the wall clock" : "")
     << (s.uses_tick_filter() ? "" : ", tick filter off") << "), status " << sum.status() << "\n\n"
     << timing_md(sum) << "\nIPC floor (hub and " << floor.workers << " processes over pipes, "
     << floor.rounds << " rounds): median " << floor.median_us << " µs, p99 " << floor.p99_us << " µs, "
     << floor.ctx_switches_per_round << " context switches and " << floor.cpu_us_per_round
     << " µs CPU per round. The fleet's median tick is "
     << (floor.median_us > 0 ? tick_us / floor.median_us : 0.0) << " x floor.\n\n"
     << cost_md(cost);
  std::filesystem::create_directories(o.out);
  records::write_text_file(o.out + "/tick.md", md.str());
  records::write_json_file(o.out + "/tick.json", sum.tick_timing_json());
  std::cout << md.str() << "results: " << o.out << "/tick.md, tick.json\n";
  return sum.status() == "ok" ? 0 : 1;
}

}  // namespace maptr::deploy
