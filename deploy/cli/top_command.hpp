#pragma once
// `maptr top [--run DIR] [--once] [--rate X] [--domain D]`: a live view of a running fleet
// (deploy/top/); on a finished run, of a replay of its recording.
#include <CLI/CLI.hpp>
#include <string>

namespace maptr::deploy::cli {

struct TopArgs {
  std::string run_dir;     ///< "" : the newest running fleet under runs/
  bool once = false;       ///< print one plain-text snapshot and exit
  double timeout_s = 120;  ///< --once: wait at most this long for the fleet's first tick, s
  int width = 80;          ///< --once: line width
  double rate = 0;         ///< a finished run: replay at X times the recorded pace; 0: not given (1)
  int domain = -1;         ///< a finished run: the replay's DDS domain; -1: a free one
};

CLI::App* add_top_command(CLI::App& app, TopArgs& a);

/// Exit code 0; 1 when no tick arrived in time (or a replay failed or stalled); 2 no fleet, a
/// finished run without a recording, or --rate/--domain on a live run. `bin_dir`: the folder of
/// the maptr executable (it runs `maptr replay`).
int cmd_top(const TopArgs& a, const std::string& bin_dir);

}  // namespace maptr::deploy::cli
