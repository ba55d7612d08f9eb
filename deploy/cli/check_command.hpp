#pragma once
// `maptr check RUN [--property NAME[:ARG] ...] [--junit FILE]`: properties of a finished run
// checked over its summary, trace and recording (deploy/fleet/run_properties.hpp), one line per
// property with its verdict, the first tick where it broke and why; `--list` prints the
// properties (with --markdown: docs/PROPERTIES.md).
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "deploy/fleet/run_properties.hpp"
#include "records/junit.hpp"

namespace maptr::deploy::cli {

struct CheckArgs {
  std::string run;                      ///< a run folder
  std::vector<std::string> properties;  ///< NAME[:ARG]; none: every property with its default
  std::string junit;                    ///< a JUnit XML file to write, one test case per property
  bool list = false;
  bool markdown = false;
};

CLI::App* add_check_command(CLI::App& app, CheckArgs& a);

/// Parses --property values; throws std::invalid_argument("--property ...") naming the bad one.
std::vector<properties::Spec> property_specs(const std::vector<std::string>& values);

/// Checks `specs` over the finished run in `run_dir`, one printed line per property (and one
/// JUnit case each into `cases` when given); returns the verdicts. Throws std::runtime_error
/// when the run has no history to check.
std::vector<properties::Verdict> check_run(const std::string& run_dir, const std::vector<properties::Spec>& specs,
                                           std::vector<records::JunitCase>* cases = nullptr);

/// RUN_DIR/repro.yaml for a run that broke: its resolved scenario (RUN_DIR/scenario.yaml, else
/// `fallback_scenario`) under what broke; its path, "" when there is no scenario to copy.
std::string write_repro(const std::string& run_dir, const std::vector<std::string>& what_broke,
                        const std::string& trace_sha256, const std::string& fallback_scenario = "");
/// Exit code 0 when every property holds, 1 when one breaks, 2 on a bad property, a run folder
/// that is not one or a JUnit file that cannot be written.
int cmd_check(const CheckArgs& a);

}  // namespace maptr::deploy::cli
