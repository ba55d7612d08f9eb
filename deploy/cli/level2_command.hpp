#pragma once
// `maptr level2`: the Level-2 problem of one side in steady cruise, for every N_a: the
// objective, the voltage each active motor needs, its efficiency and the side's electrical
// power, and the exhaustive search's choice. The same model/ code the group controllers run.
#include <CLI/CLI.hpp>

#include "deploy/cli/run_command.hpp"

namespace maptr::deploy::cli {

struct Level2Args {
  RunArgs robot;  ///< the scenario and its overrides (agents, gross mass, motor, speed)
  std::string battery_V;  ///< battery voltage, V; empty: the scenario's full battery
};

CLI::App* add_level2_command(CLI::App& app, Level2Args& a);

/// Prints the table; exit code 0, or 2 for a bad scenario.
int cmd_level2(const Level2Args& a);

}  // namespace maptr::deploy::cli
