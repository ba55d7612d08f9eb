#pragma once
// `maptr experiment NAME`: the paper's experiments, each run on the real multi-process fleet
// (one launch() per scenario variant), written as CSV, a markdown table and PNG plots.
#include <string>
#include <vector>

namespace maptr::deploy {

struct ExperimentOptions {
  std::string name;  ///< table-pow | weights | voltages | agents | battery | wear | failures | turns | faults
  bool quick = false;      ///< the short variant used by the test suite
  std::string out;         ///< output folder (created)
  std::string bin_dir;     ///< where maptr_plant & co. are
  std::string source_dir;  ///< project source (deploy/scenarios/default.yaml)
  int domain = 0;          ///< DDS domain id for every run
  double tick_hz = 0;      ///< Level-1 / plant tick rate; 0: the experiment's default
  std::string command;     ///< the command line the files name ("": maptr experiment NAME ...)
};

/// The tick rate an experiment runs at unless told otherwise: 100 Hz (the scenario default) for
/// failures, faults and turns, whose detection times are counted in ticks; 20 Hz for the long missions and
/// large fleets (see docs/results/RESULTS.md, "Tick rate").
double default_tick_hz(const std::string& name);

/// Names of the experiments, in the order `maptr experiment --help` lists them.
std::vector<std::string> experiment_names();

/// Runs one experiment; prints a progress line per run; returns the process exit code
/// (0 when every run ended ok or degraded as the experiment expects, 2 for an unknown name).
int run_experiment(const ExperimentOptions& o);

}  // namespace maptr::deploy
