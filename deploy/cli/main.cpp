// maptr: the command-line front end. Each subcommand is one function; this file only
// dispatches (`maptr run|fields|level2|experiment|compare|bench|fuzz|kill|restart|pause|resume|kill-host|partition|heal|soak|check|shrink|top|ps|replay|plot`).
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <exception>
#include <functional>
#include <iostream>
#include <vector>

#include "deploy/cli/check_command.hpp"
#include "deploy/cli/fields_command.hpp"
#include "deploy/cli/fleet_signal.hpp"
#include "deploy/cli/fuzz_command.hpp"
#include "deploy/cli/level2_command.hpp"
#include "deploy/cli/paths.hpp"
#include "deploy/cli/record_commands.hpp"
#include "deploy/cli/run_command.hpp"
#include "deploy/cli/shrink_command.hpp"
#include "deploy/cli/soak_command.hpp"
#include "deploy/cli/study_commands.hpp"
#include "deploy/cli/top_command.hpp"
#include "deploy/fleet/environment_check.hpp"

using namespace maptr::deploy::cli;

namespace {

/// Every subcommand's options, and what runs it once parsed.
class Commands {
 public:
  /// Registers the subcommands on `app` in the order `maptr --help` lists them; `bin` is the
  /// folder of the processes a fleet starts.
  Commands(CLI::App& app, const std::string& bin) {
    auto signal = [&](const char* name, SignalArgs& a) {
      return Entry{add_signal_command(app, name, a), [name, &a] { return cmd_signal(name, a); }};
    };
    entries_ = {
        {add_run_command(app, run_), [this, bin] { return cmd_run(run_, bin); }},
        {add_fields_command(app, fields_), [this] { return cmd_fields(fields_); }},
        {add_level2_command(app, level2_), [this] { return cmd_level2(level2_); }},
        {add_reach_command(app, reach_), [this] { return cmd_reach(reach_); }},
        {add_experiment_command(app, experiment_), [this, bin] { return cmd_experiment(experiment_, bin); }},
        {add_bench_command(app, bench_), [this, bin] { return cmd_bench(bench_, bin); }},
        {add_compare_command(app, compare_), [this, bin] { return cmd_compare(compare_, bin); }},
        {add_fuzz_command(app, fuzz_), [this, bin] { return cmd_fuzz(fuzz_, bin); }},
        signal("kill", kill_),
        signal("restart", restart_),
        {add_top_command(app, top_), [this, bin] { return cmd_top(top_, bin); }},
        {add_ps_command(app, ps_), [this] { return cmd_ps(ps_); }},
        {add_replay_command(app, replay_), [this] { return cmd_replay(replay_); }},
        {add_plot_command(app, plot_), [this] { return cmd_plot(plot_); }},
        signal("pause", pause_),
        signal("resume", resume_),
        {add_soak_command(app, soak_), [this, bin] { return cmd_soak(soak_, bin); }},
        {add_check_command(app, check_), [this] { return cmd_check(check_); }},
        {add_shrink_command(app, shrink_), [this, bin] { return cmd_shrink(shrink_, bin); }},
        signal("kill-host", kill_host_),
        signal("partition", partition_),
        signal("heal", heal_),
    };
  }
  Commands(const Commands&) = delete;
  Commands& operator=(const Commands&) = delete;

  /// Runs the subcommand that was parsed; 2 if none was.
  int run_parsed() const {
    for (const auto& e : entries_)
      if (e.command->parsed()) return e.run();
    return 2;
  }

 private:
  struct Entry {
    CLI::App* command;
    std::function<int()> run;
  };
  RunArgs run_;
  FieldsArgs fields_;
  Level2Args level2_;
  ReachArgs reach_;
  ExperimentArgs experiment_;
  BenchArgs bench_;
  CompareArgs compare_;
  FuzzArgs fuzz_;
  CheckArgs check_;
  ShrinkArgs shrink_;
  SignalArgs kill_, restart_, pause_, resume_, kill_host_, partition_, heal_;
  TopArgs top_;
  PsArgs ps_;
  ReplayArgs replay_;
  PlotArgs plot_;
  SoakArgs soak_;
  std::vector<Entry> entries_;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"MAPTR: the multi-agent payload transport robot as a distributed DDS system"};
  app.require_subcommand(1);
  const Commands commands(app, bin_dir(argv[0]));
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
    return commands.run_parsed();
  } catch (const std::exception& e) {
    std::cerr << "maptr: " << e.what() << "\n";
    return 1;
  }
}
