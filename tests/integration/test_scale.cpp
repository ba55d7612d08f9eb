// Scale test (ctest label `scale`, part of `deploy/maptr test`): a 64-agent fleet, 68 processes
// plus the discovery server, for 2 simulated seconds, its data on shared memory.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/integration/fleet_runner.hpp"

using maptr::testing::CliResult;
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

TEST(Bench, TheFloorBenchWritesOneRowPerSizeAndWorkingSet) {
  TempDir tmp;
  const std::string out = tmp.path() + "/floor";
  const CliResult r = run_cli({"bench", "floor", "--agents", "1,5", "--touch-kb", "0,64", "--out", out}, out, 300);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream csv(out + "/floor.csv");
  std::string header, line;
  ASSERT_TRUE(std::getline(csv, header));
  EXPECT_EQ(header.rfind("agents,workers,touch_kb,median_us", 0), 0u) << header;
  std::vector<std::string> rows;
  while (std::getline(csv, line)) rows.push_back(line.substr(0, line.find(',', line.find(',', line.find(',') + 1) + 1)));
  EXPECT_EQ(rows, (std::vector<std::string>{"1,4,0", "5,8,0", "1,4,64", "5,8,64"}));
  EXPECT_TRUE(std::filesystem::exists(out + "/floor.md"));
  const CliResult bad = run_cli({"bench", "floor", "--agents", "-3", "--out", out + "-bad"}, out + "-bad", 60);
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("'-3' is not a positive number"), std::string::npos) << bad.output;
}
