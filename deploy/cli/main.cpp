// maptr: the command-line front end. Each subcommand is one function; this file only
// dispatches (`maptr run|fields|level2|experiment|compare|bench|fuzz|kill|restart|pause|resume|kill-host|partition|heal|soak|top|ps|replay|plot`).
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <exception>
#include <iostream>

#include "deploy/cli/fields_command.hpp"
#include "deploy/cli/fleet_signal.hpp"
#include "deploy/cli/fuzz_command.hpp"
#include "deploy/cli/level2_command.hpp"
#include "deploy/cli/paths.hpp"
#include "deploy/cli/record_commands.hpp"
#include "deploy/cli/run_command.hpp"
#include "deploy/cli/soak_command.hpp"
#include "deploy/cli/study_commands.hpp"
#include "deploy/cli/top_command.hpp"
#include "deploy/fleet/environment.hpp"

using namespace maptr::deploy::cli;

int main(int argc, char** argv) {
  CLI::App app{"MAPTR: the multi-agent payload transport robot as a distributed DDS system"};
  app.require_subcommand(1);
  RunArgs run_args;
  Level2Args level2_args;
  ExperimentArgs experiment_args;
  BenchArgs bench_args;
  FuzzArgs fuzz_args;
  SignalArgs kill_args, restart_args, pause_args, resume_args, kill_host_args, partition_args, heal_args;
  SoakArgs soak_args;
  TopArgs top_args;
  PsArgs ps_args;
  auto* run = add_run_command(app, run_args);
  FieldsArgs fields_args;
  auto* fields = add_fields_command(app, fields_args);
  auto* level2 = add_level2_command(app, level2_args);
  ReachArgs reach_args;
  auto* reach = add_reach_command(app, reach_args);
  auto* experiment = add_experiment_command(app, experiment_args);
  auto* bench = add_bench_command(app, bench_args);
  CompareArgs compare_args;
  auto* compare = add_compare_command(app, compare_args);
  auto* fuzz = add_fuzz_command(app, fuzz_args);
  auto* kill = add_signal_command(app, "kill", kill_args);
  auto* restart = add_signal_command(app, "restart", restart_args);
  auto* top = add_top_command(app, top_args);
  auto* ps = add_ps_command(app, ps_args);
  ReplayArgs replay_args;
  PlotArgs plot_args;
  auto* replay = add_replay_command(app, replay_args);
  auto* plot = add_plot_command(app, plot_args);
  auto* pause = add_signal_command(app, "pause", pause_args);
  auto* resume = add_signal_command(app, "resume", resume_args);
  auto* soak = add_soak_command(app, soak_args);
  auto* kill_host = add_signal_command(app, "kill-host", kill_host_args);
  auto* partition = add_signal_command(app, "partition", partition_args);
  auto* heal = add_signal_command(app, "heal", heal_args);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help prints and exits 0; any usage error (unknown option, a value outside its set)
    // exits 2, like a bad scenario.
    return app.exit(e) == 0 ? 0 : 2;
  }
  // The environment variables that choose how fleets run are input too: checked before anything starts.
  if (const auto bad = maptr::deploy::fleet::environment_error([](const char* n) { return std::getenv(n); })) {
    std::cerr << "maptr: " << *bad << "\n";
    return 2;
  }
  // Every subcommand turns bad input into exit 2 with the option or field named; anything that
  // still escapes (an unexpected error) is reported here instead of aborting the program.
  try {
    if (run->parsed()) return cmd_run(run_args, bin_dir(argv[0]));
    if (fields->parsed()) return cmd_fields(fields_args);
    if (experiment->parsed()) return cmd_experiment(experiment_args, bin_dir(argv[0]));
    if (bench->parsed()) return cmd_bench(bench_args, bin_dir(argv[0]));
    if (compare->parsed()) return cmd_compare(compare_args, bin_dir(argv[0]));
    if (fuzz->parsed()) return cmd_fuzz(fuzz_args, bin_dir(argv[0]));
    if (level2->parsed()) return cmd_level2(level2_args);
    if (reach->parsed()) return cmd_reach(reach_args);
    if (kill->parsed()) return cmd_signal("kill", kill_args);
    if (restart->parsed()) return cmd_signal("restart", restart_args);
    if (top->parsed()) return cmd_top(top_args, bin_dir(argv[0]));
    if (ps->parsed()) return cmd_ps(ps_args);
    if (replay->parsed()) return cmd_replay(replay_args);
    if (plot->parsed()) return cmd_plot(plot_args);
    if (pause->parsed()) return cmd_signal("pause", pause_args);
    if (resume->parsed()) return cmd_signal("resume", resume_args);
    if (soak->parsed()) return cmd_soak(soak_args, bin_dir(argv[0]));
    if (kill_host->parsed()) return cmd_signal("kill-host", kill_host_args);
    if (partition->parsed()) return cmd_signal("partition", partition_args);
    if (heal->parsed()) return cmd_signal("heal", heal_args);
  } catch (const std::exception& e) {
    std::cerr << "maptr: " << e.what() << "\n";
    return 1;
  }
  return 2;
}
