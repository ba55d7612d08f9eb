#pragma once
// `maptr compare SCENARIO --set FIELD=V1,V2 ...`: the user's own scenario run once per
// combination of values, one fleet at a time, into one folder (resumed like an experiment):
// compare.md / compare.csv (energy, mileage, distance, path error, mean active agents, battery
// discharge, status, trace hash, saving against the first variant), summary.json and
// compare.png (speed, active agents, energy and battery of every variant on common axes).
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "deploy/studies/experiments/experiments.hpp"

namespace maptr::deploy {

struct CompareOptions {
  ExperimentOptions o;            ///< out, bin_dir, source_dir, domain (name is "compare")
  std::string scenario;           ///< the scenario file
  std::vector<std::string> sets;  ///< "FIELD=V1,V2,..." (default: mode=ec,all)
  std::string duration;           ///< --duration, as `maptr run --duration` ("" : the file's)
};

/// One variant: its folder id (e.g. "mode-ec_agents-32"), its label ("mode=ec agents=32") and
/// its scenario, validated.
struct CompareVariant {
  std::string id, label;
  config::Scenario s;
};

/// Every combination of the --set values (the first --set varies slowest), each scenario read
/// from the file, with --duration and the values set through the field table. Throws
/// config::ScenarioError naming the option, the value and the rule (nothing has started).
std::vector<CompareVariant> compare_variants(const CompareOptions& c);

/// Runs the variants (compare_variants(c)) and writes the files; returns the process exit code
/// (0: every variant ended ok; 3: one ended degraded; 1: one aborted or the comparison was interrupted).
int run_compare(const CompareOptions& c, const std::vector<CompareVariant>& variants);

}  // namespace maptr::deploy
