#pragma once
// `maptr kill TARGET` and `maptr restart TARGET`: commands to a running fleet's launcher.
#include <CLI/CLI.hpp>
#include <string>

namespace maptr::deploy::cli {

struct SignalArgs {
  std::string target;   ///< process name, e.g. L3, group-R, central
  std::string run_dir;  ///< "" : the newest running fleet under runs/
};

/// The `kill` or `restart` subcommand (`action`), bound to `a`.
CLI::App* add_signal_command(CLI::App& app, const std::string& action, SignalArgs& a);

/// The newest run folder under runs/ whose launcher is still listening; "" when none.
std::string latest_live_run();

/// Sends "ACTION TARGET" to the fleet; exit code 0, 1 when it could not be sent, 2 no fleet.
int cmd_signal(const std::string& action, const SignalArgs& a);

}  // namespace maptr::deploy::cli
