#pragma once
// `maptr fuzz`: long runs of the libFuzzer targets that tests/fuzz/run.sh builds with clang
// (fuzz_scenario: the scenario parser; fuzz_samples: DDS samples through the readers' checks).
// Each target runs for the given seconds from its committed seed corpus with the options of
// tests/fuzz/<target>.flags. In OUT: corpus/<name>/ (inputs found), crashes/<name>/ (each
// crashing input, as libFuzzer writes it: crash-<sha1>, leak-..., timeout-..., oom-...) and
// fuzz_<name>.log.
#include <string>
#include <vector>

namespace maptr::deploy {

struct FuzzOptions {
  std::string target = "all";  ///< scenario | samples | all
  int seconds = 60;            ///< per target
  std::string out;             ///< output folder
  std::string fuzz_build;      ///< the clang build of tests/fuzz (its bin/ holds the targets)
  std::string source_dir;
};

/// The targets `target` names ("all": every one).
std::vector<std::string> fuzz_targets(const std::string& target);

/// Runs the targets one after the other; prints executions, exec/s and crashes per target.
/// Returns 0, 1 when a target crashed, 2 when a target is not built (saying how to build it).
int run_fuzz(const FuzzOptions& o);

}  // namespace maptr::deploy
