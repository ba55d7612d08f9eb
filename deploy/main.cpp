// maptr: the command-line front end. `maptr run [SCENARIO.yaml] [overrides]` launches a fleet.
#include <CLI/CLI.hpp>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "deploy/bench.hpp"
#include "deploy/experiments.hpp"
#include "control/level2/problem.hpp"
#include "model/motor.hpp"
#include "deploy/faults.hpp"
#include "deploy/launcher.hpp"
#include "config/scenario.hpp"

namespace fs = std::filesystem;
using maptr::config::Scenario;
using maptr::config::ScenarioError;

namespace {

std::string default_scenario() { return std::string(MAPTR_SOURCE_DIR) + "/deploy/scenarios/default.yaml"; }

std::string bin_dir(const char* argv0) {
  std::error_code ec;
  fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) self = fs::absolute(argv0);
  return self.parent_path().string();
}

std::string unique_run_dir(const std::string& base, const std::string& name) {
  std::time_t now = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%Y%m%d-%H%M%S", std::localtime(&now));
  std::string dir = base + "/" + stamp + "-" + name;
  for (int i = 2; fs::exists(dir); ++i) dir = base + "/" + stamp + "-" + name + "-" + std::to_string(i);
  return dir;
}

struct RunArgs {
  std::string scenario;
  int agents = 0;
  double gross_kg = 0, duration = 0, speed = -1;
  std::string motor, mode, out;
  bool realtime = false, quiet = false;
  int domain = -1, trace_every = 0;
  double tick_hz = 0;
  std::vector<std::string> kills, restarts, external;
  long long chaos = -1;
  std::string transport = "auto";
};

void add_faults(Scenario& s, const std::vector<std::string>& specs, const std::string& action) {
  for (const auto& spec : specs) {
    const auto at = spec.find('@');
    if (at == std::string::npos)
      throw ScenarioError("--" + action + " " + spec + ": expected TARGET@SECONDS, e.g. L3@120");
    maptr::config::FaultSpec f;
    f.target = spec.substr(0, at);
    f.action = action;
    try {
      f.at_s = std::stod(spec.substr(at + 1));
    } catch (...) {
      throw ScenarioError("--" + action + " " + spec + ": time '" + spec.substr(at + 1) + "' is not a number");
    }
    s.faults.push_back(f);
  }
}

/// The scenario file (or the default one) with the robot options of the command line applied.
Scenario load_robot(const RunArgs& a) {
  Scenario s = maptr::config::load_scenario(a.scenario.empty() ? default_scenario() : a.scenario);
  if (a.agents) s.robot.agents = a.agents;
  if (a.gross_kg) s.robot.gross_mass_kg = a.gross_kg;
  if (!a.motor.empty()) s.robot.motor = maptr::model::motor_type(a.motor);
  return s;
}

int cmd_run(const RunArgs& a, const char* argv0) {
  Scenario s;
  try {
    s = load_robot(a);
    if (!a.mode.empty()) s.mode = a.mode;
    if (a.duration) s.duration_s = a.duration;
    if (a.realtime) s.realtime = true;
    if (a.trace_every) s.trace_every = a.trace_every;
    if (a.tick_hz) s.tick_hz = a.tick_hz;
    if (a.speed >= 0)
      for (auto& seg : s.trajectory.segments)
        if (seg.type != "stop") seg.speed_mps = a.speed;
    if (a.duration && s.trajectory.total_duration() < s.duration_s)
      s.trajectory.segments.back().duration_s += s.duration_s - s.trajectory.total_duration();
    add_faults(s, a.kills, "kill");
    add_faults(s, a.restarts, "restart");
    if (a.chaos >= 0)
      for (const auto& f : maptr::deploy::chaos_schedule(static_cast<unsigned>(a.chaos), s)) s.faults.push_back(f);
    s.validate();
    for (const auto& name : a.external) {
      int side = 0, idx = 0;
      if (!maptr::config::parse_agent_name(name, side, idx) || idx >= s.robot.per_side())
        throw ScenarioError("--external " + name + ": not an agent of this scenario (L0..L" +
                            std::to_string(s.robot.per_side() - 1) + ", R0..)");
    }
  } catch (const ScenarioError& e) {
    std::cerr << "maptr: " << e.what() << "\n";
    return 2;
  } catch (const maptr::model::ParamError& e) {
    std::cerr << "maptr: " << e.what() << "\n";
    return 2;
  }
  maptr::deploy::LaunchOptions o;
  o.scenario = s;
  o.run_dir = a.out.empty() ? unique_run_dir("runs", s.name) : a.out;
  o.bin_dir = bin_dir(argv0);
  o.progress = !a.quiet;
  o.external = a.external;
  o.transport = a.transport;
  o.chaos_seed = a.chaos;
  o.domain = a.domain >= 0 ? a.domain : (std::getenv("MAPTR_DOMAIN") ? std::atoi(std::getenv("MAPTR_DOMAIN")) : 0);
  if (const std::string why = maptr::deploy::domain_problem(o.domain, s.robot.agents); !why.empty()) {
    std::cerr << "maptr: " << why << "\n";
    return 2;
  }
  fs::create_directories(o.run_dir + "/logs");
  auto log = std::make_shared<spdlog::logger>(
      "launcher", std::make_shared<spdlog::sinks::basic_file_sink_mt>(o.run_dir + "/logs/launcher.log"));
  log->flush_on(spdlog::level::info);
  std::cerr << "maptr: run folder " << o.run_dir << "\n";
  nlohmann::json summary;
  try {
    summary = maptr::deploy::launch(o, *log);
  } catch (const std::exception& e) {
    std::cerr << "maptr: " << e.what() << "\n";
    return 1;
  }
  std::cout << maptr::deploy::human_summary(summary);
  std::cout << "results     " << o.run_dir << "/summary.json, trace.csv, logs/\n";
  const std::string st = summary.value("status", "");
  return st == "ok" ? 0 : (st.rfind("degraded", 0) == 0 ? 3 : 1);
}

/// The newest run folder under runs/ whose launcher is still listening.
std::string latest_live_run() {
  std::string best;
  fs::file_time_type best_t{};
  std::error_code ec;
  if (!fs::exists("runs", ec)) return "";
  for (const auto& d : fs::directory_iterator("runs", ec)) {
    const fs::path fifo = d.path() / "control";
    if (!fs::is_fifo(fifo, ec)) continue;
    const auto t = fs::last_write_time(d.path(), ec);
    if (best.empty() || t > best_t) best = d.path().string(), best_t = t;
  }
  return best;
}

/// `maptr level2`: the Level-2 problem of one side in steady cruise, for every N_a: the
/// objective, the voltage each active motor needs, its efficiency and the side's electrical
/// power, and the exhaustive search's choice. The same model/ code the group controllers run.
int cmd_level2(const RunArgs& a, double battery_V) {
  Scenario s;
  try {
    s = load_robot(a);
    s.validate();
  } catch (const std::exception& e) {
    std::cerr << "maptr: " << e.what() << "\n";
    return 2;
  }
  const double v = a.speed >= 0 ? a.speed : s.trajectory.segments.front().speed_mps;
  maptr::control::Level2Problem p;
  p.robot = s.robot;
  p.live = s.robot.per_side();
  p.v_x = v;
  p.phidot_ref_L = p.phidot_ref_R = v / s.robot.wheel_radius_m;
  p.battery_V = battery_V > 0 ? battery_V : s.robot.battery.y;
  p.horizon = s.control.horizon;
  p.step_s = s.control.horizon_step_s;
  const double ph = p.phidot_ref_L;
  std::printf("Level 2, one side in steady cruise: %d agents, %.1f kg, motor %s, %.2f m/s (%.1f rad/s), V_B %.2f V\n",
              s.robot.agents, s.robot.gross_mass_kg, s.robot.motor.type.c_str(), v, ph, p.battery_V);
  std::printf("%4s %10s %10s %9s %9s %12s  %s\n", "N_a", "J (of H)", "V need", "V need/VB", "eta", "P side W",
              "feasible");
  for (int n = 1; n <= p.live; ++n) {
    p.n_other = n;
    const double vn = maptr::control::required_voltage(p, n);
    const double i = maptr::model::armature_current(s.robot.motor, vn, ph);
    std::printf("%4d %10.4f %10.3f %9.3f %9.4f %12.2f  %s\n", n, maptr::control::horizon_efficiency(p, n), vn,
                vn / p.battery_V, maptr::model::efficiency(s.robot.motor, vn, ph), n * vn * i,
                maptr::control::level2_feasible(p, n) ? "yes" : "no (needs more than V_B)");
  }
  p.n_other = 0;
  const auto c = maptr::control::exhaustive_level2(p);
  std::printf("oracle: N_a = %d per side%s\n", c.n_active,
              c.feasible ? "" : " (no N_a can hold the speed: every live agent runs)");
  return 0;
}

int cmd_signal(const std::string& action, const std::string& target, std::string run_dir) {
  if (run_dir.empty()) run_dir = latest_live_run();
  if (run_dir.empty()) {
    std::cerr << "maptr: no running fleet found under runs/ (give its folder with --run DIR)\n";
    return 2;
  }
  try {
    maptr::deploy::send_command(run_dir, action, target);
  } catch (const std::exception& e) {
    std::cerr << "maptr: " << e.what() << "\n";
    return 1;
  }
  std::cout << "maptr: sent '" << action << " " << target << "' to the fleet in " << run_dir << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"MAPTR: the multi-agent payload transport robot as a distributed DDS system"};
  app.require_subcommand(1);
  RunArgs ra;
  auto* run = app.add_subcommand("run", "launch the fleet (plant, central, 2 groups, N agents) for one scenario");
  run->add_option("scenario", ra.scenario, "scenario YAML (default: deploy/scenarios/default.yaml)");
  run->add_option("--agents", ra.agents, "number of agents N (multiple of 4)");
  run->add_option("--gross-kg", ra.gross_kg, "gross mass, kg");
  run->add_option("--motor", ra.motor, "motor type I or II");
  run->add_option("--mode", ra.mode, "all (every agent, the paper's NO) or ec (energy-conscious)");
  run->add_option("--duration", ra.duration, "simulated seconds");
  run->add_option("--speed", ra.speed, "speed of every moving segment, m/s");
  run->add_flag("--realtime", ra.realtime, "pace ticks to the wall clock");
  run->add_option("--out", ra.out, "results folder (default runs/<date>-<scenario>)");
  run->add_option("--domain", ra.domain, "DDS domain id (default $MAPTR_DOMAIN or 0)")->check(CLI::Range(0, 232));
  run->add_option("--trace-every", ra.trace_every, "write every n-th tick to trace.csv");
  run->add_option("--tick-hz", ra.tick_hz, "Level-1 control and plant tick rate, Hz (default: the scenario's, 100)");
  run->add_option("--kill", ra.kills, "kill a process at a simulated time, e.g. L3@120 (repeatable)");
  run->add_option("--restart", ra.restarts, "restart a killed process, e.g. L3@300 (repeatable)");
  run->add_option("--chaos", ra.chaos, "random kills and restarts of agents and controllers, reproducible from SEED");
  run->add_option("--external", ra.external, "an agent you start yourself (the launcher prints the command)");
  run->add_option("--transport", ra.transport, "data transport: shm, udp or auto (shm up to 64 agents)")
      ->check(CLI::IsMember({"auto", "shm", "udp"}));
  run->add_flag("--quiet", ra.quiet, "no progress lines");
  RunArgs la;
  double l2_battery = 0;
  auto* l2c = app.add_subcommand("level2", "the Level-2 problem of one side in steady cruise, for every N_a");
  l2c->add_option("scenario", la.scenario, "scenario YAML (default: deploy/scenarios/default.yaml)");
  l2c->add_option("--agents", la.agents, "number of agents N");
  l2c->add_option("--gross-kg", la.gross_kg, "gross mass, kg");
  l2c->add_option("--motor", la.motor, "motor type I or II");
  l2c->add_option("--speed", la.speed, "cruise speed, m/s (default: the first segment's)");
  l2c->add_option("--battery-v", l2_battery, "battery voltage, V (default: full, 23.4 V)");
  maptr::deploy::ExperimentOptions eo;
  int exp_domain = -1;
  auto* expc = app.add_subcommand("experiment", "run one of the paper's experiments on real fleets");
  expc->add_option("name", eo.name, "experiment")
      ->required()
      ->check(CLI::IsMember(maptr::deploy::experiment_names()));
  expc->add_flag("--quick", eo.quick, "short variant (what the test suite runs)");
  expc->add_option("--out", eo.out, "output folder (default runs/<date>-experiment-<name>)");
  expc->add_option("--domain", exp_domain, "DDS domain id (default $MAPTR_DOMAIN or 0)")->check(CLI::Range(0, 232));
  expc->add_option("--tick-hz", eo.tick_hz, "tick rate, Hz (default 100 for failures, 20 for the others)")
      ->check(CLI::Range(1.0, 10000.0));
  maptr::deploy::BenchOptions bo;
  std::string bench_agents;
  auto* benchc = app.add_subcommand("bench", "measure the distributed system: scale (N agents) or tick (latency)");
  benchc->add_option("what", bo.what, "scale or tick")->required()->check(CLI::IsMember({"scale", "tick"}));
  benchc->add_option("--agents", bench_agents, "comma-separated fleet sizes (scale) or one size (tick)");
  benchc->add_option("--duration", bo.duration_s, "simulated seconds per run")->check(CLI::PositiveNumber);
  benchc->add_option("--out", bo.out, "output folder (default runs/<date>-bench-<what>)");
  benchc->add_option("--domain", exp_domain, "DDS domain id (default $MAPTR_DOMAIN or 0)")->check(CLI::Range(0, 232));
  benchc->add_flag("--replot", bo.replot, "scale: redraw scale.png from the scale.csv in --out, run nothing");
  std::string target, run_dir;
  auto* killc = app.add_subcommand("kill", "SIGKILL a process of a running fleet (e.g. L3, group-R, central)");
  killc->add_option("target", target, "process name")->required();
  killc->add_option("--run", run_dir, "run folder (default: the newest running one under runs/)");
  auto* restartc = app.add_subcommand("restart", "start a killed process of a running fleet again");
  restartc->add_option("target", target, "process name")->required();
  restartc->add_option("--run", run_dir, "run folder (default: the newest running one under runs/)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help prints and exits 0; any usage error (unknown option, a value outside its set)
    // exits 2, like a bad scenario.
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (run->parsed()) return cmd_run(ra, argv[0]);
  if (expc->parsed()) {
    eo.bin_dir = bin_dir(argv[0]);
    eo.source_dir = MAPTR_SOURCE_DIR;
    if (eo.out.empty()) eo.out = unique_run_dir("runs", "experiment-" + eo.name + (eo.quick ? "-quick" : ""));
    if (exp_domain >= 0)
      eo.domain = exp_domain;
    else if (const char* d = std::getenv("MAPTR_DOMAIN"))
      eo.domain = std::atoi(d);
    return maptr::deploy::run_experiment(eo);
  }
  if (benchc->parsed()) {
    bo.bin_dir = bin_dir(argv[0]);
    bo.source_dir = MAPTR_SOURCE_DIR;
    if (!bench_agents.empty()) {
      bo.agents.clear();
      std::stringstream ss(bench_agents);
      for (std::string x; std::getline(ss, x, ',');) {
        try {
          bo.agents.push_back(std::stoi(x));
        } catch (...) {
          std::cerr << "maptr: --agents " << bench_agents << ": '" << x << "' is not a number\n";
          return 2;
        }
      }
    } else if (bo.what == "tick") {
      bo.agents = {16};
    }
    if (bo.out.empty()) bo.out = unique_run_dir("runs", "bench-" + bo.what);
    bo.domain = exp_domain >= 0 ? exp_domain : (std::getenv("MAPTR_DOMAIN") ? std::atoi(std::getenv("MAPTR_DOMAIN")) : 0);
    return maptr::deploy::run_bench(bo);
  }
  if (l2c->parsed()) return cmd_level2(la, l2_battery);
  if (killc->parsed()) return cmd_signal("kill", target, run_dir);
  if (restartc->parsed()) return cmd_signal("restart", target, run_dir);
  return 2;
}
