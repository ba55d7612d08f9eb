#pragma once
// `maptr shrink SCENARIO --property NAME[:ARG] ... [--out DIR]`: a failing scenario (a soak's or
// a run's repro.yaml) reduced to a smallest one that still breaks a property: delta debugging
// over its faults (deploy/fleet/shrink.hpp), then its duration cut to just after the break;
// fleets run one at a time, a line per step. Writes DIR/minimal.yaml and DIR/shrink.json
// (steps, fleets run, wall time); an interrupted shrink resumes from DIR/shrink-cache.json.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace maptr::deploy::cli {

struct ShrinkArgs {
  std::string scenario;                 ///< the failing scenario
  std::vector<std::string> properties;  ///< NAME[:ARG]; the case fails when any of them breaks
  std::string out;                      ///< default runs/<date>-shrink-<name>
  int domain = -1;
};

CLI::App* add_shrink_command(CLI::App& app, ShrinkArgs& a);
/// Exit code 0 with minimal.yaml written, 1 when the scenario does not break the properties
/// (nothing to shrink) or a fleet could not run, 2 on bad input, 130 when interrupted.
int cmd_shrink(const ShrinkArgs& a, const std::string& bin_dir);

}  // namespace maptr::deploy::cli
