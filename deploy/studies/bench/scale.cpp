// `maptr bench scale`: discovery time, real-time factor, CPU and memory against the number of
// agents, one fleet per size (each in a child process: a fleet that fails at a size is recorded,
// not fatal to the bench).
#include <sys/resource.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "deploy/fleet/isolated_launch.hpp"
#include "deploy/report/gnuplot.hpp"
#include "deploy/studies/bench/bench_parts.hpp"
#include "deploy/studies/bench/cost_watch.hpp"
#include "deploy/studies/bench/dds_floor.hpp"
#include "deploy/studies/bench/floor.hpp"
#include "deploy/studies/bench/memory.hpp"
#include "deploy/studies/bench/proc_stats.hpp"
#include "deploy/studies/bench/scale_verdict.hpp"
#include "records/junit.hpp"
#include "records/result_table.hpp"
#include "records/study_columns.hpp"
#include "records/summary.hpp"

namespace maptr::deploy {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr double kScaleSpeed = 10.0;  ///< m/s
constexpr int kScaleTraceEvery = 10;  ///< trace rows
constexpr std::size_t kStatusMdChars = 70;
constexpr double kKiB = 1024.0;
/// Processes besides the agents that answer every tick: 2 groups and central.
constexpr int kAnswersBesideAgents = 3;

/// PSS per agent process the bench draws as its target, MB.
constexpr double kPssTargetMB = 8.0;

/// `plot` of column `y` (an expression of column values) against N, one curve per control mode
/// (rows of one host only), without the closing newline.
std::string plot_by_mode(const std::string& y) {
  std::string cmd = "plot ";
  const char* modes[] = {"ec", "all"};
  for (const char* m : modes)
    cmd += std::string(cmd.size() > 5 ? ", " : "") + "'scale.csv' using \"agents\":(strcol(\"mode\") eq \"" +
           m + "\" && column(\"hosts\") == 1 ? " + y + " : NaN) with linespoints title 'mode " + m + "'";
  return cmd;
}

/// The plots of scale.png, by column name.
std::string plot_body() {
  return "set multiplot layout 2,3 title 'MAPTR scale-up on this machine (lock-step, one host)'\n"
         "set logscale x 2\nset grid\nset xlabel 'agent processes N'\nset key top left\n"
         "set ylabel 'seconds'\nset title 'launch to all matched'\n" +
         plot_by_mode("column(\"discovery_s\")") +
         "\nset ylabel 'simulated s per wall s'\nset title 'real-time factor at 100 Hz (log scale)'\n"
         "set logscale y\nset key top right\n" +
         plot_by_mode("column(\"real_time_factor\")") + ", 1 with lines dt 2 title 'real time'\n" +
         "set ylabel 'fleet tick / floor tick'\nset title 'tick against the IPC floor (same run)'\n"
         "unset logscale y\nset key top left\n" +
         plot_by_mode("column(\"x_floor\")") +
         "\nset ylabel 'CPU s per simulated s'\nset title 'CPU cost (log scale)'\nset logscale y\n" +
         plot_by_mode("column(\"cpu_s_per_sim_s\")") +
         "\nunset logscale y\nset ylabel 'ms'\nset title 'plant tick, median'\n" +
         plot_by_mode("column(\"tick_median_us\")/1000") +
         "\nset ylabel 'MB'\nset title 'PSS per agent process, median'\nset yrange [0:*]\n" +
         plot_by_mode("column(\"pss_agent_median_kB\")/1024") + ", " + std::to_string(kPssTargetMB) +
         " with lines dt 2 title 'target'\nunset multiplot\n";
}

void plot(const std::string& dir) {
  report::draw_plot(dir, "scale",
                    "made by `maptr bench scale`; redraw with `maptr bench scale --replot --out DIR`",
                    report::PlotFrame{"1500,900", ""}, plot_body());
}

/// The default scenario with n agents on `hosts` hosts (over ssh with --ssh), every moving
/// segment at kScaleSpeed, the last one stretched to the bench's duration.
config::Scenario scale_scenario(const BenchOptions& o, int n, const std::string& mode, int hosts) {
  config::Scenario s = config::load_scenario(o.source_dir + "/deploy/scenarios/paper.yaml");
  s.robot.agents = n;
  if (hosts > 1) s.hosts.count = hosts;
  s.hosts.ssh = hosts > 1 && o.ssh;
  s.mode = mode;
  s.duration_s = o.duration_s;
  s.trace_every = kScaleTraceEvery;
  s.record = o.record;
  s.realtime = o.realtime;
  s.tick_filter = o.tick_filter;
  if (o.plant_priority >= 0) s.plant_priority = o.plant_priority;
  for (auto& seg : s.trajectory.segments)
    if (seg.type != "stop") seg.speed_mps = kScaleSpeed;
  if (s.trajectory.total_duration() < s.duration_s)
    s.trajectory.segments.back().duration_s += s.duration_s - s.trajectory.total_duration();
  s.validate();
  return s;
}

/// Bytes the hosts sent into the bridge per tick (0 on one host).
double bridge_bytes_per_tick(const records::Summary& sum) {
  const double ticks = sum.number_or(records::summary_key::kTicks, 0);
  double sent = 0;
  for (const auto& h : sum.data().value("hosts", json::array())) sent += h.value("bytes_sent", 0.0);
  return ticks > 0 ? sent / ticks : 0.0;
}

/// The memory columns of a row: an agent's PSS (median, largest) and the fleet's, kB and MB.
json memory_json(const FleetMemory& mem) {
  const long pss_max =
      mem.agent_pss_kB.empty() ? 0 : *std::max_element(mem.agent_pss_kB.begin(), mem.agent_pss_kB.end());
  return {{"pss_agent_median_kB", median(mem.agent_pss_kB)},
          {"pss_agent_median_MB", median(mem.agent_pss_kB) / kKiB},
          {"pss_agent_max_kB", pss_max},
          {"pss_agent_max_MB", pss_max / kKiB},
          {"pss_total_kB", mem.total_pss_kB},
          {"pss_total_MB", mem.total_pss_kB / kKiB}};
}

/// What the slowest 1 % of the ticks had in common, beside all ticks (plant.tick_timing_us.slowest_1pct).
json slowest_json(const records::Summary& sum) {
  const json s = sum.tick_timing_json().value("slowest_1pct", json::object());
  const json slow = s.value("slowest", json::object()), all = s.value("all", json::object());
  json row;
  for (const char* k : {"last_agent_pct", "last_group_pct", "last_central_pct", "level2_solving_pct", "traced_pct"}) {
    row[std::string("slow_") + k] = slow.value(k, 0.0);
    row[std::string("all_") + k] = all.value(k, 0.0);
  }
  return row;
}

/// "N16-ec", "N16-ec-hosts3", "N16-ec-hosts3-ssh": a row's run folder and JUnit case.
std::string variant_name(const BenchOptions& o, int n, const std::string& mode, int hosts) {
  return "N" + std::to_string(n) + "-" + mode + (hosts > 1 ? "-hosts" + std::to_string(hosts) : "") +
         (hosts > 1 && o.ssh ? "-ssh" : "");
}

/// The plant's first tick (tick 0), µs: the write of the first tick opens every reader's port.
double first_tick_us(const records::Summary& sum) {
  for (const auto& t : sum.tick_timing_json().value("slowest_1pct", json::object()).value("ticks", json::array()))
    if (t.value("tick", -1LL) == 0) return t.value("us", 0.0);
  return 0.0;  // not among the five slowest
}

/// The DDS floor of a fleet of n agents: its N + 3 answering processes, its tick, the domain it
/// ran on (now free), the plant's priority on the hub.
DdsFloorOptions dds_floor_options(const BenchOptions& o, const config::Scenario& s, int n) {
  DdsFloorOptions d;
  d.workers = n + kAnswersBesideAgents;
  d.agents = n;
  d.domain = o.domain;
  d.hub_priority = s.plant_priority;
  return d;
}

/// The tick's distribution (the plant's figures) beside both floors of the same shape.
json timing_json(const records::Summary& sum, const FloorResult& floor, const DdsFloorResult& dds) {
  const records::TickTiming tick = sum.tick_timing("tick"), period = sum.tick_timing("period");
  return {
      {"tick_median_us", tick.median},
      {"tick_median_ms", tick.median / 1000.0},
      {"tick_p99_us", tick.p99},
      {"tick_p99_ms", tick.p99 / 1000.0},
      {"tick_mean_us", tick.mean},
      {"tick_p90_us", tick.p90},
      {"tick_max_us", tick.max},
      {"period_median_us", period.median},
      {"period_mean_us", period.mean},
      {"mean_over_median", period.median > 0 ? period.mean / period.median : 0.0},
      {"floor_median_us", floor.median_us},
      {"x_floor", floor.median_us > 0 ? tick.median / floor.median_us : 0.0},
      {"dds_floor_median_us", dds.median_us},
      {"dds_floor_mean_us", dds.mean_us},
      {"x_dds_floor", dds.median_us > 0 ? tick.median / dds.median_us : 0.0},
      {"dds_floor_cpu_us_per_round", dds.cpu_us_per_round},
      {"dds_floor_resent", dds.resent},
      {"dds_floor_first_round_us", dds.first_round_us},
      {"first_tick_us", first_tick_us(sum)},
      {"dds_floor_problem", dds.measured ? "" : dds.problem}};
}

/// One fleet size in one control mode on `hosts` hosts (1: this machine, no namespaces): its
/// row of the table.
json measure(const BenchOptions& o, int n, const std::string& mode, int hosts) {
  const std::string run_dir = o.out + "/runs/" + variant_name(o, n, mode, hosts);
  config::Scenario s = scale_scenario(o, n, mode, hosts);
  FleetMemory mem;
  FleetCost cost;
  const double cpu0 = cpu_seconds(RUSAGE_CHILDREN);
  // The hypervisor's share of this machine's CPU time during the fleet and during the floor: on
  // a shared VM, what makes one sitting's ratios differ from another's.
  const auto machine0 = read_machine_cpu();
  const records::Summary sum(launch_isolated(LaunchOptions::of(s, run_dir, o.bin_dir, o.domain),
                                             run_dir + "/maptr.out", [&](const std::atomic<bool>& done) {
                                               mem = sample_memory(run_dir, done);
                                               cost = watch_fleet_cost(run_dir, cost_window(s.ticks()), done);
                                             }));
  const double cpu = cpu_seconds(RUSAGE_CHILDREN) - cpu0;
  const auto machine1 = read_machine_cpu();
  const double sim = sum.number_or(records::summary_key::kSimTime, 0),
               wall = sum.number_or(records::summary_key::kWallTime, 0);
  const std::string status = sum.status();
  // The floor of the same shape, measured right after the fleet, on the same machine state.
  const FloorResult floor = measure_floor(n + kAnswersBesideAgents);
  const auto machine2 = read_machine_cpu();
  // And Fast DDS's own floor, the fleet's transport and QoS with nothing else.
  const DdsFloorResult dds = measure_dds_floor(dds_floor_options(o, s, n));
  const auto steal = [](const std::optional<MachineCpu>& a, const std::optional<MachineCpu>& b) {
    return a && b ? steal_percent(*a, *b) : 0.0;
  };
  json row = {
      {"agents", n},
      {"mode", mode},
      {"record", o.record},
      {"realtime", o.realtime ? "yes" : "no"},
      {"tick_filter", s.uses_tick_filter() ? "yes" : "no"},
      {"plant_scheduling", sum.data().value("plant", json::object()).value("loop_scheduling", "")},
      {"hosts", hosts},
      {"started_by", hosts > 1 ? (o.ssh ? "ssh" : "ip netns") : ""},
      {"wall_s", wall},
      {"status", status.substr(0, status.find(':'))},
      {"status_full", status},
      {"status_text", status.size() > kStatusMdChars ? status.substr(0, kStatusMdChars) + "..." : status},
      {"discovery_s", sum.number_or(records::summary_key::kDiscovery, 0)},
      {"ticks_per_wall_s", wall > 0 ? sum.number_or(records::summary_key::kTicks, 0) / wall : 0.0},
      {"real_time_factor", sum.number_or(records::summary_key::kRealTimeFactor, 0)},
      {"cpu_s_per_sim_s", sim > 0 ? cpu / sim : 0.0},
      {"samples_per_tick", n + 4},  // one PlantTick, N AgentReply, 2 GroupStatus, 1 CentralCommand
      {"bridge_bytes_per_tick", bridge_bytes_per_tick(sum)},
      {"floor_cs_per_round", floor.ctx_switches_per_round},
      {"floor_cpu_us_per_round", floor.cpu_us_per_round},
      {"steal_pct_fleet", steal(machine0, machine1)},
      {"steal_pct_floor", steal(machine1, machine2)}};
  row.update(timing_json(sum, floor, dds));
  row.update(memory_json(mem));
  row.update(fleet_cost_json(cost));
  row.update(slowest_json(sum));
  return row;
}

int replot(const BenchOptions& o) {
  if (!fs::exists(o.out + "/scale.csv")) {
    std::cerr << "maptr: bench scale --replot: no " << o.out << "/scale.csv\n";
    return 2;
  }
  plot(o.out);
  std::cerr << "maptr: redrew " << o.out << "/scale.png\n";
  return 0;
}

}  // namespace

int bench_scale(const BenchOptions& o) {
  if (o.replot) return replot(o);
  fs::create_directories(o.out);
  records::ResultTable t;
  t.cols = records::columns::bench_scale();
  records::ResultTableWriter csv(o.out + "/scale.csv", t.cols);
  const ScaleThresholds limits{o.min_rtf, o.max_floor_ratio};
  std::vector<std::string> headlines;
  std::vector<records::JunitCase> cases;
  int missed = 0;
  std::vector<int> host_counts = {1};
  if (o.hosts > 1) host_counts.push_back(o.hosts);
  for (const std::string& mode : o.modes)  // a mode's rows together: its curves are unbroken
    for (int n : o.agents)
      for (int hosts : host_counts) {
        std::cerr << "maptr: bench scale N=" << n << ", mode " << mode << ", on " << hosts << " host(s) ..."
                  << std::flush;
        const json row = measure(o, n, mode, hosts);
        csv.append(row);  // a later size that fails leaves the earlier rows
        t.rows.push_back(row);
        std::cerr << " CPU steal " << row["steal_pct_fleet"].get<double>() << " %\n";
        const auto misses = scale_misses(row, limits);
        headlines.push_back(scale_headline(row, misses));
        std::cerr << "maptr: " << headlines.back() << "\n";
        std::string failure;
        for (const auto& m : misses) failure += (failure.empty() ? "" : "; ") + m;
        cases.push_back(
            {variant_name(o, n, mode, hosts), "maptr.bench.scale", row.value("wall_s", 0.0), failure});
        missed += !misses.empty();
      }
  records::write_text_file(o.out + "/scale.md", t.md());
  plot(o.out);
  if (!o.junit.empty()) records::write_text_file(o.junit, records::junit_xml("maptr bench scale", cases));
  for (const auto& h : headlines) std::cout << h << "\n";
  std::cout << "bench scale: " << cases.size() - missed << " of " << cases.size() << " sizes pass";
  if (o.min_rtf >= 0) std::cout << ", --min-rtf " << o.min_rtf;
  if (o.max_floor_ratio >= 0) std::cout << ", --max-floor-ratio " << o.max_floor_ratio;
  std::cout << "\nresults: " << o.out << "/scale.csv, scale.md (every column), scale.png"
            << (o.junit.empty() ? "" : ", " + o.junit) << "\n";
  return missed > 0 ? 1 : 0;
}

}  // namespace maptr::deploy
