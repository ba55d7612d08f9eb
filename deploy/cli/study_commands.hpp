#pragma once
// `maptr experiment NAME`, `maptr compare SCENARIO` and `maptr bench scale|tick`: their options and how the defaults
// (output folder, domain, fleet sizes) are filled in.
#include <CLI/CLI.hpp>
#include <string>

#include "deploy/studies/bench/bench.hpp"
#include "deploy/studies/experiments/compare.hpp"
#include "deploy/studies/experiments/experiments.hpp"

namespace maptr::deploy::cli {

struct ExperimentArgs {
  ExperimentOptions o;
  int domain = -1;
};

struct CompareArgs {
  CompareOptions c;
  int domain = -1;
};

struct BenchArgs {
  BenchOptions o;
  std::string agents;  ///< comma-separated fleet sizes
  int domain = -1;
};

CLI::App* add_experiment_command(CLI::App& app, ExperimentArgs& a);
CLI::App* add_bench_command(CLI::App& app, BenchArgs& a);
CLI::App* add_compare_command(CLI::App& app, CompareArgs& a);
int cmd_compare(CompareArgs a, const std::string& bin_dir);

int cmd_experiment(ExperimentArgs a, const std::string& bin_dir);
int cmd_bench(BenchArgs a, const std::string& bin_dir);

}  // namespace maptr::deploy::cli
