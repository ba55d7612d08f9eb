#pragma once
// `maptr check RUN [--property NAME[:ARG] ...] [--junit FILE]`: properties of a finished run
// checked over its summary, trace and recording (deploy/fleet/run_properties.hpp), one line per
// property with its verdict, the first tick where it broke and why; `--list` prints the
// properties (with --markdown: docs/PROPERTIES.md).
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace maptr::deploy::cli {

struct CheckArgs {
  std::string run;                      ///< a run folder
  std::vector<std::string> properties;  ///< NAME[:ARG]; none: every property with its default
  std::string junit;                    ///< a JUnit XML file to write, one test case per property
  bool list = false;
  bool markdown = false;
};

CLI::App* add_check_command(CLI::App& app, CheckArgs& a);
/// Exit code 0 when every property holds, 1 when one breaks, 2 on a bad property, a run folder
/// that is not one or a JUnit file that cannot be written.
int cmd_check(const CheckArgs& a);

}  // namespace maptr::deploy::cli
