#pragma once
// `maptr top [--run DIR] [--once]`: a live view of a running fleet (deploy/top/).
#include <CLI/CLI.hpp>
#include <string>

namespace maptr::deploy::cli {

struct TopArgs {
  std::string run_dir;     ///< "" : the newest running fleet under runs/
  bool once = false;       ///< print one plain-text snapshot and exit
  double timeout_s = 120;  ///< --once: wait at most this long for the fleet's first tick, s
  int width = 80;          ///< --once: line width
};

CLI::App* add_top_command(CLI::App& app, TopArgs& a);

/// Exit code 0; 1 when no tick arrived in time; 2 no fleet (or a finished run, which needs a
/// recording to replay).
int cmd_top(const TopArgs& a);

}  // namespace maptr::deploy::cli
