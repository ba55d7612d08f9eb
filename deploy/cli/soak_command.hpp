#pragma once
// `maptr soak --seed S --faults N [--agents A]`: fleets of the soak scenario back to back, each
// with seeded random kills, restarts, pauses and resumes of agents, groups, central and the
// discovery server, until N faults were applied; after each fleet the checks of
// deploy/fleet/soak.hpp plus no process of the fleet left and no growth of /dev/shm, and the
// --property checks of `maptr check`. A failing fleet leaves repro.yaml in its folder (its
// scenario with the faults as they acted: `maptr run repro.yaml` breaks it again). Prints a
// line per fleet and a final table, writes OUT/soak.json (and --junit FILE); exit 0 when every
// check passed, 1 when one failed, 2 on bad input.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace maptr::deploy::cli {

struct SoakArgs {
  long long seed = 1;
  long long faults = 20;  ///< faults to apply over the whole soak (kills, restarts, pauses, resumes)
  int agents = 8;
  int outages = 8;       ///< random outages drawn per fleet
  std::string scenario;  ///< default: deploy/scenarios/soak.yaml
  std::string out;       ///< default: runs/<date>-soak-<seed>
  int domain = -1;
  double fleet_timeout_s = 600.0;  ///< a fleet still running after this wall time fails
  std::vector<std::string> properties;  ///< NAME[:ARG] checked over each fleet (maptr check)
  std::string junit;                    ///< a JUnit XML file, one test case per fleet
};

CLI::App* add_soak_command(CLI::App& app, SoakArgs& a);
int cmd_soak(const SoakArgs& a, const std::string& bin_dir);

}  // namespace maptr::deploy::cli
