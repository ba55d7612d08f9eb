#include "deploy/cli/study_commands.hpp"

#include <iostream>
#include <sstream>

#include "deploy/cli/paths.hpp"
#include "deploy/fleet/hosts.hpp"

namespace maptr::deploy::cli {

namespace {
/// `--tick-hz` of an experiment: the accepted range, Hz.
constexpr double kMinTickHz = 1.0, kMaxTickHz = 10000.0;
/// `maptr bench tick` without --agents.
constexpr int kTickBenchAgents = 16;
}  // namespace

CLI::App* add_experiment_command(CLI::App& app, ExperimentArgs& a) {
  auto* c = app.add_subcommand("experiment", "run one of the paper's experiments (or the project's own: failures, turns, faults) on real fleets");
  c->add_option("name", a.o.name, "experiment")->required()->check(CLI::IsMember(experiment_names()));
  c->add_flag("--quick", a.o.quick, "short variant (what the test suite runs)");
  c->add_option("--out", a.o.out, "output folder (default runs/<date>-experiment-<name>)");
  c->add_option("--domain", a.domain, "DDS domain id (default $MAPTR_DOMAIN or 0)")
      ->check(CLI::Range(0, kMaxDomain));
  c->add_option("--tick-hz", a.o.tick_hz, "tick rate, Hz (default 100 for failures, turns and faults, 20 for the others)")
      ->check(CLI::Range(kMinTickHz, kMaxTickHz));
  return c;
}

CLI::App* add_bench_command(CLI::App& app, BenchArgs& a) {
  auto* c = app.add_subcommand(
      "bench", "measure the distributed system: scale (N agents), tick (latency) or floor (IPC floor, no DDS)");
  c->add_option("what", a.o.what, "scale, tick or floor")
      ->required()
      ->check(CLI::IsMember({"scale", "tick", "floor"}));
  c->add_option("--agents", a.agents, "comma-separated fleet sizes (scale, floor) or one size (tick)");
  c->add_option("--touch-kb", a.o.touch_kb,
                "floor: comma-separated KiB each process writes to per round (default 0,128,512)")
      ->delimiter(',')
      ->check(CLI::Range(0, 1 << 20));
  c->add_option("--duration", a.o.duration_s, "simulated seconds per run")->check(CLI::PositiveNumber);
  c->add_option("--out", a.o.out, "output folder (default runs/<date>-bench-<what>)");
  c->add_option("--domain", a.domain, "DDS domain id (default $MAPTR_DOMAIN or 0)")
      ->check(CLI::Range(0, kMaxDomain));
  c->add_flag("--ssh", a.o.ssh,
              "scale: the --hosts runs start every process over ssh (an ssh server per host)");
  c->add_option("--hosts", a.o.hosts, "scale: also run each size on N hosts (namespaces; needs root)")
      ->check(CLI::Range(2, 64));
  c->add_option("--modes", a.o.modes,
                "scale: comma-separated control modes run at every size (default ec,all)")
      ->delimiter(',')
      ->check(CLI::IsMember({"ec", "all"}));
  c->add_option("--record", a.o.record,
                "what each fleet records in run.mcap: all (default, as `maptr run`), plant or none")
      ->check(CLI::IsMember({"all", "plant", "none"}));
  c->add_flag("--realtime", a.o.realtime,
              "pace the fleets' ticks to the wall clock, as `maptr run --realtime`: every tick starts "
              "from idle processes (the tick median is still publish to integration, without the pause)");
  c->add_option("--tick-filter", a.o.tick_filter,
                "auto (default, as `maptr run`: on in ec, off in all); true: an idle agent takes only the ticks "
                "it answers; false: every tick")
      ->check(CLI::IsMember({"auto", "true", "false"}));
  c->add_option("--plant-priority", a.o.plant_priority,
                "SCHED_FIFO priority of the plant's lock-step thread, 1-99 (default: a run's, 1); 0: normal "
                "scheduling")
      ->check(CLI::Range(0, 99));
  c->add_flag("--replot", a.o.replot, "scale: redraw scale.png from the scale.csv in --out, run nothing");
  c->add_option("--min-rtf", a.o.min_rtf, "scale: a size whose real-time factor is below this misses (exit 1)")
      ->check(CLI::NonNegativeNumber);
  c->add_option("--max-floor-ratio", a.o.max_floor_ratio,
                "scale: a size whose median tick is more than this many times the IPC floor's misses (exit 1)")
      ->check(CLI::PositiveNumber);
  c->add_option("--junit", a.o.junit, "scale: write JUnit XML here, one test case per size and mode");
  return c;
}

CLI::App* add_compare_command(CLI::App& app, CompareArgs& a) {
  auto* c = app.add_subcommand("compare",
                               "run a scenario once per combination of field values (default: mode=ec,all) and "
                               "compare energy, mileage, path and battery (compare.md, compare.csv, compare.png)");
  c->add_option("scenario", a.c.scenario, "scenario YAML")->required();
  c->add_option("--set", a.c.sets,
                "FIELD=V1,V2,... : one variant per value (repeatable: every combination), e.g. mode=ec,all or "
                "gross_mass_kg=20,30 (`maptr fields` lists the fields)");
  c->add_option("--duration", a.c.duration, "simulated seconds of every variant (as maptr run --duration)");
  c->add_option("--out", a.c.o.out, "output folder (default runs/<date>-compare-<scenario>); run again to resume");
  c->add_option("--domain", a.domain, "DDS domain id (default $MAPTR_DOMAIN or 0)")->check(CLI::Range(0, kMaxDomain));
  return c;
}

int cmd_compare(CompareArgs a, const std::string& bin_dir) {
  a.c.o.name = "compare";
  a.c.o.bin_dir = bin_dir;
  a.c.o.source_dir = source_dir();
  a.c.o.domain = resolve_domain(a.domain);
  std::vector<CompareVariant> variants;
  const bool read = input_read([&] {
    variants = compare_variants(a.c);  // bad input: exit 2 before anything starts
    if (a.c.o.out.empty()) a.c.o.out = unique_run_dir("runs", "compare-" + variants.front().s.name);
  });
  if (!read) return 2;
  std::string cmd = "maptr compare " + a.c.scenario;
  for (const auto& s : a.c.sets) cmd += " --set " + s;
  if (!a.c.duration.empty()) cmd += " --duration " + a.c.duration;
  a.c.o.command = cmd + " --out " + a.c.o.out;
  return run_compare(a.c, variants);
}

int cmd_experiment(ExperimentArgs a, const std::string& bin_dir) {
  a.o.bin_dir = bin_dir;
  a.o.source_dir = source_dir();
  if (a.o.out.empty())
    a.o.out = unique_run_dir("runs", "experiment-" + a.o.name + (a.o.quick ? "-quick" : ""));
  a.o.domain = resolve_domain(a.domain);
  return run_experiment(a.o);
}

int cmd_bench(BenchArgs a, const std::string& bin_dir) {
  a.o.bin_dir = bin_dir;
  a.o.source_dir = source_dir();
  if (!a.agents.empty()) {
    a.o.agents.clear();
    std::stringstream ss(a.agents);
    for (std::string x; std::getline(ss, x, ',');) {
      try {
        std::size_t used = 0;
        a.o.agents.push_back(std::stoi(x, &used));
        if (used != x.size() || a.o.agents.back() < 1) throw std::invalid_argument(x);
      } catch (...) {
        std::cerr << "maptr: --agents " << a.agents << ": '" << x << "' is not a positive number\n";
        return 2;
      }
    }
  } else if (a.o.what == "tick") {
    a.o.agents = {kTickBenchAgents};
  }
  if (a.o.ssh && a.o.hosts < 2) {
    std::cerr << "maptr: bench --ssh: the ssh rehearsal needs --hosts N (2 or more)\n";
    return 2;
  }
  if (a.o.hosts > 1)
    if (const std::string why = fleet::hosts_root_problem(); !why.empty()) {
      std::cerr << "maptr: bench " << why << "\n";
      return 2;
    }
  if (a.o.out.empty()) a.o.out = unique_run_dir("runs", "bench-" + a.o.what);
  a.o.domain = resolve_domain(a.domain);
  return run_bench(a.o);
}

}  // namespace maptr::deploy::cli
