#pragma once
// `maptr run [SCENARIO.yaml] [overrides]`: launches one fleet.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "config/scenario.hpp"

namespace maptr::deploy::cli {

/// The command-line overrides of a scenario, as typed (empty: keep the scenario's value). Each
/// goes through the scenario's field table (config::set_field), so a bad value is refused
/// exactly as it would be in the file.
struct RunArgs {
  std::string scenario;
  std::string agents, gross_kg, motor, mode, duration, speed, trace_every, tick_hz, record, tick_filter,
      plant_priority, driver, record_compression;
  std::string out;
  bool realtime = false, quiet = false, secure = false;
  int domain = -1;
  std::vector<std::string> kills, restarts, pauses, resumes, external;
  std::vector<std::string> kill_hosts, partitions, heals, placement;
  std::vector<std::string> agent_faults, clears;  ///< --fault L3:open@20, --clear L3@40
  int hosts = 0;  ///< --hosts N (0: the scenario's)
  bool ssh = false;  ///< --ssh
  long long chaos = -1;
  std::string transport = "auto";
  double stall_timeout_s = 0.0;  ///< --stall-timeout S (0: the launcher's default)
  std::vector<std::string> properties;  ///< --property NAME[:ARG], checked at the end (maptr check)
};

/// The `run` subcommand and its options, bound to `a`.
CLI::App* add_run_command(CLI::App& app, RunArgs& a);

/// The scenario file (or the default one) with every override of `a` applied: the one place
/// where a command-line option becomes a scenario field. Throws ScenarioError or ParamError.
config::Scenario scenario_from(const RunArgs& a);

/// Runs the fleet; exit code 0 ok, 3 degraded, 1 failed or a --property broke (the run folder
/// then holds repro.yaml), 2 bad scenario or options.
int cmd_run(const RunArgs& a, const std::string& bin_dir);

}  // namespace maptr::deploy::cli
