// Scale test (ctest label `scale`, part of `deploy/maptr test`): a 64-agent fleet, 68 processes
// plus the discovery server, for 2 simulated seconds, its data on shared memory.
#include <gtest/gtest.h>

#include "tests/integration/fleet_runner.hpp"

using maptr::testing::run_args;
using maptr::testing::run_cli;
using maptr::testing::TempDir;

TEST(Fleet, SixtyFourAgentProcessesJoinAndFinish) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(run_args(out, {"--agents", "64", "--duration", "2"}), out, 400);
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.summary["status"], "ok");
  EXPECT_EQ(r.summary["ticks"], 200);
  EXPECT_EQ(r.summary["transport"], "shm");  // data on shared memory at every size
  // Every one of the 68 processes announced itself, ran the lock-step and ended cleanly.
  ASSERT_EQ(r.summary["processes"].size(), 68u);
  for (const auto& p : r.summary["processes"]) EXPECT_EQ(p["exit_code"].get<int>(), 0) << p.dump();
  EXPECT_EQ(r.summary["plant"]["live_agents"]["L"], 32);
  EXPECT_EQ(r.summary["plant"]["live_agents"]["R"], 32);
  EXPECT_EQ(r.summary["plant"]["declared_dead_by_deadline"], 0);
}
