// Level 2 off the tick's path (ctest label `integration`): a decision is solved on the group's
// worker thread and applied control.level2_defer_s later, so how long a solve takes cannot
// change a run. Real fleets through `maptr run` on a private domain.
#include <gtest/gtest.h>

#include <cstdlib>
#include <set>

#include "records/level2_log.hpp"
#include "tests/hooks/hooks.hpp"
#include "tests/integration/fleet_runner.hpp"

using maptr::testing::run_args;
using maptr::testing::run_cli;
using maptr::testing::TempDir;
using maptr::testing::write_file;

namespace {

/// An EC run whose load changes: 10 m/s, 5 m/s, then 8 m/s (Level 2 changes its count).
constexpr const char* kChangingLoad =
    "name: l2-changes\nagents: 16\nmode: ec\nduration_s: 24\n"
    "trajectory:\n  segments:\n"
    "    - {type: straight, speed_mps: 10, duration_s: 8}\n"
    "    - {type: straight, speed_mps: 5, duration_s: 8}\n"
    "    - {type: straight, speed_mps: 8, duration_s: 8}\n";

/// Runs `maptr run ARGS` (the product's binaries, or with delay_ms not empty the hooked ones
/// whose Level-2 solves take that much longer); returns trace_sha256.
std::string run_sha(const TempDir& tmp, const std::string& name, std::vector<std::string> args,
                    const std::string& delay_ms = "") {
  const std::string out = tmp.path() + "/" + name;
  const auto r = [&] {
    if (delay_ms.empty()) return run_cli(run_args(out, std::move(args)), out, 300);
    const maptr::testing::HookedBinaries hook(maptr::test_hooks::kLevel2DelayEnv, delay_ms);
    return run_cli(run_args(out, std::move(args)), out, 300);
  }();
  EXPECT_FALSE(r.timed_out) << r.output;
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.summary.value("status", ""), "ok") << r.summary.dump();
  return r.summary.value("trace_sha256", "");
}

/// The counts Level 2 applied on side 0 of a run (its Level-2 log, in order).
std::vector<int> applied_counts(const std::string& run_dir) {
  std::vector<int> n;
  for (const auto& rec : maptr::records::read_level2_log(maptr::records::level2_log_path(run_dir, 0)))
    n.push_back(static_cast<int>(rec.n_target));
  return n;
}

}  // namespace

TEST(Level2Defer, ASlowSolveGivesTheSameTrace) {
  TempDir tmp;
  const std::vector<std::string> args = {"--duration", "8"};
  const std::string fast = run_sha(tmp, "fast", args);
  const std::string slow = run_sha(tmp, "slow", args, "30");  // 30 ms per solve, 3 ticks of 10 ms
  EXPECT_EQ(fast.size(), 64u);
  EXPECT_EQ(fast, slow);
  EXPECT_GE(applied_counts(tmp.path() + "/slow").size(), 4u);  // Level 2 did decide
  for (const char* side : {"L", "R"}) {  // and the hooked groups did pause after each solve
    const std::string log = maptr::testing::read_text(tmp.path() + "/slow/logs/group-" + side + ".log");
    EXPECT_NE(log.find("followed by a 30 ms pause"), std::string::npos) << log;
  }
}

TEST(Level2Defer, ChangingDecisionsRunTwiceAndWithASlowSolveGiveOneTrace) {
  TempDir tmp;
  const std::string scen = tmp.path() + "/changes.yaml";
  write_file(scen, kChangingLoad);
  const std::string a = run_sha(tmp, "a", {scen});
  const std::string b = run_sha(tmp, "b", {scen});
  const std::string slow = run_sha(tmp, "slow", {scen}, "30");
  EXPECT_EQ(a.size(), 64u);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a, slow);
  // Level 2 changed its decision several times in that run.
  const std::vector<int> n = applied_counts(tmp.path() + "/a");
  int changes = 0;
  for (std::size_t i = 1; i < n.size(); ++i) changes += n[i] != n[i - 1];
  EXPECT_GE(changes, 2) << "counts applied: " << ::testing::PrintToString(n);
  EXPECT_GE(std::set<int>(n.begin(), n.end()).size(), 2u);
}
