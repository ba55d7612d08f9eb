#include "deploy/cli/run_command.hpp"

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "comm/dds/dds.hpp"
#include "deploy/cli/check_command.hpp"
#include "deploy/cli/paths.hpp"
#include "deploy/fleet/fault_schedule.hpp"
#include "deploy/fleet/hosts.hpp"
#include "deploy/fleet/launcher.hpp"
#include "model/params.hpp"

namespace maptr::deploy::cli {

using config::Scenario;
using config::ScenarioError;

namespace {

/// Exit codes of `maptr run`.
constexpr int kExitOk = 0, kExitFailed = 1, kExitBadInput = 2, kExitDegraded = 3;


/// "--fault L3:torque=0.5@20" and the like: the option's text first in every error.
[[noreturn]] void bad_option(const std::string& action, const std::string& spec, const std::string& why) {
  throw ScenarioError("--" + action + " " + spec.substr(0, 80) + ": " + why);
}

/// `text` read whole as a number into `out`; false when it is empty, not a number or has more.
bool whole_number(const std::string& text, double& out) {
  std::size_t used = 0;
  try {
    out = std::stod(text, &used);
  } catch (...) {
    return false;
  }
  return used != 0 && used == text.size();
}

/// Reads --fault's TARGET:MODE[=VALUE] into f (the time is read by add_faults).
void read_fault_mode(const std::string& spec, const std::string& head, config::FaultSpec& f) {
  const auto colon = head.find(':');
  if (colon == std::string::npos)
    bad_option("fault", spec, "expected TARGET:MODE[=VALUE]@SECONDS, e.g. L3:open@20 or L3:torque=0.5@20");
  f.target = head.substr(0, colon);
  const std::string mode = head.substr(colon + 1);
  const auto eq = mode.find('=');
  f.mode = mode.substr(0, eq);
  if (eq == std::string::npos) return;
  const std::string value = mode.substr(eq + 1);
  if (!whole_number(value, f.value))
    bad_option("fault", spec, "faults[].value = " + value.substr(0, 80) + ": must be a number");
}

void add_faults(Scenario& s, const std::vector<std::string>& specs, const std::string& action) {
  for (const auto& spec : specs) {
    const auto at = spec.rfind('@');
    if (at == std::string::npos)
      bad_option(action, spec,
                 action == "fault" ? "expected TARGET:MODE[=VALUE]@SECONDS, e.g. L3:torque=0.5@20"
                                   : "expected TARGET@SECONDS, e.g. L3@120");
    config::FaultSpec f;
    f.action = action;
    f.origin = "--" + action + " " + spec.substr(0, 80);
    if (action == "fault")
      read_fault_mode(spec, spec.substr(0, at), f);
    else
      f.target = spec.substr(0, at);
    const std::string time = spec.substr(at + 1);
    if (!whole_number(time, f.at_s) || !std::isfinite(f.at_s) || f.at_s < 0)
      bad_option(action, spec, "faults[].at_s = " + time.substr(0, 80) + ": must be a finite number of seconds, at least 0");
    if ((action == "pause" || action == "resume") && f.target == "plant")
      bad_option(action, spec, "faults[].target = plant: the plant cannot be paused: it is the fleet's clock");
    int side = 0, index = 0;
    if (config::is_agent_fault_action(action) &&
        (!config::parse_agent_name(f.target, side, index) || index >= s.robot.per_side()))
      bad_option(action, spec, "faults[].target = " + f.target.substr(0, 80) + ": --" + action +
                                   " needs an agent of the robot (L0.." + config::agent_name(0, s.robot.per_side() - 1) +
                                   ", R0..): only a wheel's motor or its agent's software fails this way");
    std::string field;
    const std::string why = config::fault_mode_problem(f, s.robot, field);
    if (!why.empty())
      bad_option(action, spec, "faults[]." + field + " = " +
                                   (field == "mode" ? f.mode.substr(0, 80) : model::param_value(f.value)) + ": " + why);
    s.faults.push_back(f);
  }
}

/// The scenario of `maptr run`, validated, with the --external names checked.
Scenario checked_scenario(const RunArgs& a) {
  Scenario s = scenario_from(a);
  s.validate();
  if (s.hosts.enabled() && s.hosts.machines.empty())
    if (const std::string why = fleet::hosts_root_problem(); !why.empty()) throw ScenarioError(why);
  if (s.hosts.enabled()) {
    std::vector<std::string> names = {"plant", "central", "group-L", "group-R"};
    for (int side = 0; side < 2; ++side)
      for (int j = 0; j < s.robot.per_side(); ++j) names.push_back(config::agent_name(side, j));
    fleet::place_processes(names, s.hosts.count, s.hosts.placement);  // throws on a bad rule
  }
  for (const auto& name : a.external) {
    int side = 0, idx = 0;
    if (!config::parse_agent_name(name, side, idx) || idx >= s.robot.per_side())
      throw ScenarioError("--external " + name + ": not an agent of this scenario (L0..L" +
                          std::to_string(s.robot.per_side() - 1) + ", R0..)");
    for (const auto& f : s.faults)
      if (f.target == name && !config::is_agent_fault_action(f.action))
        throw ScenarioError((f.origin.empty() ? s.source + ": faults[]" : f.origin) + ": " + f.action + " of " + name +
                            ": --external " + name + " is a process the launcher does not start, so it does not " +
                            f.action + " it either");
  }
  return s;
}

std::shared_ptr<spdlog::logger> launcher_log(const std::string& run_dir) {
  std::filesystem::create_directories(run_dir + "/logs");
  auto log = std::make_shared<spdlog::logger>(
      "launcher", std::make_shared<spdlog::sinks::basic_file_sink_mt>(run_dir + "/logs/launcher.log"));
  log->flush_on(spdlog::level::info);
  return log;
}

/// The fault schedule's options: processes, hosts and agents that run on.
void add_fault_options(CLI::App* run, RunArgs& a) {
  run->add_option("--kill", a.kills, "kill a process at a simulated time, e.g. L3@120 (repeatable)");
  run->add_option("--restart", a.restarts, "restart a killed process, e.g. L3@300 (repeatable)");
  run->add_option("--pause", a.pauses,
                  "stop a process (SIGSTOP) at a simulated time, e.g. L3@120 (repeatable)");
  run->add_option("--resume", a.resumes, "continue a paused process (SIGCONT), e.g. L3@130 (repeatable)");
  run->add_option(
      "--chaos", a.chaos,
      "random kills and restarts, pauses and resumes of agents and controllers, and one agent fault (cleared 2-8 s later), reproducible from SEED");
  run->add_option("--kill-host", a.kill_hosts, "kill every process of a host and cut its link, e.g. h2@20");
  run->add_option("--partition", a.partitions, "cut a host's link at a simulated time, e.g. h2@20");
  run->add_option("--heal", a.heals, "link a cut host again, e.g. h2@30");
  run->add_option("--fault", a.agent_faults,
                  "break an agent that runs on, e.g. L3:open@20, L3:torque=0.5@20, L3:stuck=12@20, "
                  "R1:sensor=5@30, R1:erratic=2@30, L0:liar@10 (repeatable; docs/ARCHITECTURE.md \"Fault detection\")");
  run->add_option("--clear", a.clears, "end an agent's fault, e.g. L3@40 (repeatable)");
}

}  // namespace

CLI::App* add_run_command(CLI::App& app, RunArgs& a) {
  auto* run =
      app.add_subcommand("run", "launch the fleet (plant, central, 2 groups, N agents) for one scenario");
  run->add_option("scenario", a.scenario, "scenario YAML (default: deploy/scenarios/default.yaml)");
  run->add_option("--agents", a.agents, "number of agents N (multiple of 4)");
  run->add_option("--property", a.properties,
                  "check NAME[:ARG] over the run at its end, as maptr check does; one that breaks: repro.yaml, exit 1 "
                  "(repeatable)");
  run->add_option("--gross-kg", a.gross_kg, "gross mass, kg");
  run->add_option("--motor", a.motor, "motor type I or II");
  run->add_option("--driver", a.driver, "motor driver: unidirectional (no braking) or bidirectional (H-bridge)");
  run->add_option("--mode", a.mode, "all (every agent, the paper's NO) or ec (energy-conscious)");
  run->add_option("--duration", a.duration, "simulated seconds");
  run->add_option("--speed", a.speed, "speed of every moving segment, m/s");
  run->add_flag("--realtime", a.realtime, "pace ticks to the wall clock");
  run->add_option("--out", a.out, "results folder (default runs/<date>-<scenario>)");
  run->add_option("--domain", a.domain, "DDS domain id (default $MAPTR_DOMAIN or 0)")
      ->check(CLI::Range(0, kMaxDomain));
  run->add_option("--trace-every", a.trace_every, "write every n-th tick to trace.csv");
  run->add_option("--tick-hz", a.tick_hz,
                  "Level-1 control and plant tick rate, Hz (default: the scenario's, 100)");
  run->add_option("--external", a.external, "an agent you start yourself (the launcher prints the command)");
  run->add_option("--transport", a.transport, "data transport: shm, shm+udp (data on both), udp or auto (shm on one host; data on shm+udp across hosts or with --secure)")
      ->check(CLI::IsMember({"auto", "shm", "shm+udp", "udp"}));
  run->add_option("--record", a.record, "what run.mcap records: all (default), plant or none");
  run->add_option("--record-compression", a.record_compression,
                  "run.mcap's chunk compression: zstd (default), lz4 or none");
  run->add_option("--tick-filter", a.tick_filter,
                  "auto (default): on in ec, off in all; true: an idle agent takes only the ticks it answers; "
                  "false: every agent every tick");
  run->add_option("--plant-priority", a.plant_priority,
                  "SCHED_FIFO priority of the plant's lock-step thread, 1-99 (default 1); 0: normal scheduling");
  run->add_flag("--secure", a.secure,
                "DDS Security: a private CA, one certificate and permissions per process, encrypted data");
  run->add_option("--hosts", a.hosts, "run the fleet on N hosts (network namespaces; needs root)")
      ->check(CLI::Range(1, config::kMaxHosts));
  run->add_option("--place", a.placement, "put a process on a host, e.g. central=h1 (repeatable)");
  run->add_flag("--ssh", a.ssh,
                "with --hosts: an ssh server in each namespace host and every process started over ssh (the "
                "rehearsal of real machines; needs openssh-server)");
  run->add_option("--stall-timeout", a.stall_timeout_s,
                  "end the run as stalled after this many wall seconds without a tick (default 180)")
      ->check(CLI::Range(1.0, 86400.0));
  run->add_flag("--quiet", a.quiet, "no progress lines");
  add_fault_options(run, a);
  return run;
}

Scenario scenario_from(const RunArgs& a) {
  // Option -> scenario field (config/scenario.hpp lists the same mapping).
  struct Override {
    const char* option;
    const char* path;
    std::string RunArgs::*value;
  };
  static const Override kOverrides[] = {
      {"--agents", "agents", &RunArgs::agents},          {"--gross-kg", "gross_mass_kg", &RunArgs::gross_kg},
      {"--motor", "motor", &RunArgs::motor},             {"--mode", "mode", &RunArgs::mode},
      {"--tick-hz", "tick_hz", &RunArgs::tick_hz},
      {"--trace-every", "trace_every", &RunArgs::trace_every}, {"--record", "record", &RunArgs::record},
      {"--tick-filter", "tick_filter", &RunArgs::tick_filter},
      {"--record-compression", "record_compression", &RunArgs::record_compression},
      {"--plant-priority", "plant_priority", &RunArgs::plant_priority},
      {"--driver", "robot.driver", &RunArgs::driver}};
  Scenario s = config::load_scenario(a.scenario.empty() ? default_scenario() : a.scenario);
  for (const auto& o : kOverrides)
    if (!(a.*o.value).empty()) config::set_field(s, o.path, a.*o.value, o.option);
  if (!a.speed.empty()) config::set_speed(s, a.speed, "--speed");
  if (!a.duration.empty()) config::set_duration(s, a.duration, "--duration");
  if (a.realtime) s.realtime = true;
  if (a.hosts > 0) s.hosts.count = a.hosts;
  if (a.ssh) s.hosts.ssh = true;
  if (s.hosts.ssh && !s.hosts.enabled())
    throw config::ScenarioError(
        "--ssh: the rehearsal runs on namespace hosts: give --hosts N (or the scenario's hosts.count)");
  if (s.hosts.ssh && !s.hosts.machines.empty())
    throw config::ScenarioError("--ssh: the scenario lists hosts.machines; each gives its own ssh command");
  for (const auto& p : a.placement) s.hosts.placement.push_back(p);
  add_faults(s, a.kills, "kill");
  add_faults(s, a.restarts, "restart");
  add_faults(s, a.pauses, "pause");
  add_faults(s, a.resumes, "resume");
  add_faults(s, a.kill_hosts, "kill-host");
  add_faults(s, a.partitions, "partition");
  add_faults(s, a.heals, "heal");
  add_faults(s, a.agent_faults, "fault");
  add_faults(s, a.clears, "clear");
  if (a.chaos >= 0)
    for (auto f : chaos_schedule(static_cast<unsigned>(a.chaos), s)) {
      f.origin = "--chaos " + std::to_string(a.chaos) + " (its " + f.action + " of " + f.target + ")";
      s.faults.push_back(f);
    }
  return s;
}

/// The --property checks at the end of a run: a line each; when one breaks, repro.yaml in the
/// run folder and exit code 1.
static int check_properties(const std::string& run_dir, const std::vector<properties::Spec>& specs,
                     const nlohmann::json& summary, int rc) {
  std::vector<std::string> broke;
  try {
    for (const auto& v : check_run(run_dir, specs))
      if (!v.holds) broke.push_back(v.property + " at tick " + std::to_string(v.tick) + ": " + v.reason);
  } catch (const std::exception& e) {
    std::cout << "properties  not checked: " << e.what() << "\n";
    return kExitFailed;
  }
  if (broke.empty()) return rc;
  const std::string repro = write_repro(run_dir, broke, summary.value("trace_sha256", ""));
  std::cout << "properties  " << broke.size() << " of " << specs.size() << " broke"
            << (repro.empty() ? "" : "; reproducer " + repro + " (maptr run " + repro + ")") << "\n";
  return kExitFailed;
}

int cmd_run(const RunArgs& a, const std::string& bin_dir) {
  LaunchOptions o;
  std::vector<properties::Spec> specs;
  const bool read = input_read([&] {
    specs = property_specs(a.properties);
    o.scenario = checked_scenario(a);
  });
  if (!read) return kExitBadInput;
  o.run_dir = a.out.empty() ? unique_run_dir("runs", o.scenario.name) : a.out;
  o.bin_dir = bin_dir;
  o.progress = !a.quiet;
  o.external = a.external;
  o.transport = a.transport;
  o.chaos_seed = a.chaos;
  o.domain = resolve_domain(a.domain);
  o.secure = a.secure;
  o.stall_s = a.stall_timeout_s;
  for (const std::string& why : {domain_problem(o.domain, o.scenario.robot.agents), secure_problem(o)})
    if (!why.empty()) {
      std::cerr << "maptr: " << why << "\n";
      return kExitBadInput;
    }
  auto log = launcher_log(o.run_dir);
  std::cerr << "maptr: run folder " << o.run_dir << "\n";
  nlohmann::json summary;
  try {
    summary = launch(o, *log);
  } catch (const ScenarioError& e) {  // a host that cannot run the fleet: nothing started
    std::cerr << "maptr: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "maptr: " << e.what() << "\n";
    return kExitFailed;
  }
  std::cout << human_summary(summary);
  std::cout << "results     " << o.run_dir << "/summary.json, trace.csv, logs/\n";
  if (o.scenario.record != "none") std::cout << "recording   " << o.run_dir << "/run.mcap (maptr replay RUN)\n";
  if (std::filesystem::exists(o.run_dir + "/run.png")) std::cout << "picture     " << o.run_dir << "/run.png\n";
  const std::string st = summary.value("status", "");
  int rc = st == "ok" ? kExitOk : (st.rfind("degraded", 0) == 0 ? kExitDegraded : kExitFailed);
  if (!specs.empty()) rc = check_properties(o.run_dir, specs, summary, rc);
  if (comm::participant_left_open()) {
    // Fast DDS never finished deleting a participant (launcher.cpp): its factory's static
    // destructor would wait on it again, so the results are flushed and the process ends here.
    log->flush();
    std::cout.flush();
    std::fflush(nullptr);
    std::_Exit(rc);
  }
  return rc;
}

}  // namespace maptr::deploy::cli
