#pragma once
// `maptr kill TARGET`, `maptr restart TARGET`, ...: commands to a running fleet's launcher;
// `maptr ps`: the running fleets.
#include <CLI/CLI.hpp>
#include <string>

namespace maptr::deploy::cli {

struct SignalArgs {
  std::string target;   ///< process name, e.g. L3, group-R, central
  std::string run_dir;  ///< "" : the newest running fleet (registered, else under runs/)
};

/// The `kill` or `restart` subcommand (`action`), bound to `a`.
CLI::App* add_signal_command(CLI::App& app, const std::string& action, SignalArgs& a);

/// The run folder of the newest registered running fleet (deploy/fleet/registry.hpp), wherever
/// its --out is; else the newest under runs/ whose launcher is still listening; "" when none.
std::string latest_live_run();

/// What `maptr top`, `kill`, ... say when no fleet runs.
inline constexpr const char* kNoRunningFleet =
    "no running fleet (none registered, none under runs/; `maptr ps` lists them, or give its folder with --run DIR)";

struct PsArgs {
  bool json = false;
};
CLI::App* add_ps_command(CLI::App& app, PsArgs& a);
/// Lists the running fleets: folder, scenario, launcher pid, domain, simulated time.
int cmd_ps(const PsArgs& a);

/// Sends "ACTION TARGET" to the fleet; exit code 0, 1 when it could not be sent, 2 no fleet.
int cmd_signal(const std::string& action, const SignalArgs& a);

}  // namespace maptr::deploy::cli
