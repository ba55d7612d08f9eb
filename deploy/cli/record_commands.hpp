#pragma once
// `maptr replay RUN [--rate X] [--domain D]`: a recording published again on a DDS domain;
// `maptr plot RUN`: run.png drawn again from a run folder.
#include <CLI/CLI.hpp>
#include <string>

namespace maptr::deploy::cli {

struct ReplayArgs {
  std::string run;  ///< a run folder (its run.mcap) or an .mcap file
  double rate = 1.0;
  int domain = -1;
  double wait_reader_s = 5.0;
  bool with_rejected = false;  ///< also the samples the fleet dropped
  bool quiet = false;
};

struct PlotArgs {
  std::string run;
};

CLI::App* add_replay_command(CLI::App& app, ReplayArgs& a);
CLI::App* add_plot_command(CLI::App& app, PlotArgs& a);

/// Exit code 0 when every message was sent, 1 on an error, 2 on a bad argument or file.
int cmd_replay(const ReplayArgs& a);
/// Exit code 0 when run.png was drawn, 1 when not.
int cmd_plot(const PlotArgs& a);

}  // namespace maptr::deploy::cli
