#pragma once
// `maptr level2`: the Level-2 problem of one side in steady cruise, for every N_a: the
// objective, the voltage each active motor needs, its efficiency and the side's electrical
// power, and the exhaustive search's choice, in cruise or (--radius) for each side of a steady
// turn, where the inner side may brake. The same model/ code the group controllers run.
// `maptr reach`: the tightest steady-turn radius against speed (model/reach.hpp).
#include <CLI/CLI.hpp>

#include "deploy/cli/run_command.hpp"

namespace maptr::deploy::cli {

struct Level2Args {
  RunArgs robot;  ///< the scenario and its overrides (agents, gross mass, motor, driver, speed)
  std::string battery_V;  ///< battery voltage, V; empty: the scenario's full battery
  double radius_m = 0.0;  ///< a steady turn of this radius (> 0 left, < 0 right); 0: straight
};

/// `maptr reach`: the tightest radius the robot holds in a steady turn, against speed.
struct ReachArgs {
  RunArgs robot;  ///< the scenario and its overrides (agents, gross mass, motor, driver)
  std::string battery_V;
  double max_speed_mps = 0.0;  ///< 0: up to the motors' reach
};

CLI::App* add_reach_command(CLI::App& app, ReachArgs& a);
/// Prints the table; exit code 0, or 2 for a bad scenario or option.
int cmd_reach(const ReachArgs& a);

CLI::App* add_level2_command(CLI::App& app, Level2Args& a);

/// Prints the table; exit code 0, or 2 for a bad scenario.
int cmd_level2(const Level2Args& a);

}  // namespace maptr::deploy::cli
