// Scale test (ctest label `scale`, part of `deploy/maptr test`): a 64-agent fleet, 68 processes
// plus the discovery server, for 2 simulated seconds.
#include <gtest/gtest.h>

#include "tests/integration/fleet_runner.hpp"

using maptr::testing::private_domain;
using maptr::testing::run_cli;
using maptr::testing::TempDir;

namespace {
std::vector<std::string> base(const std::string& out, std::vector<std::string> extra) {
  std::vector<std::string> a = {"run"};
  a.insert(a.end(), extra.begin(), extra.end());
  for (const std::string& s : {std::string("--out"), out, std::string("--domain"), std::to_string(private_domain()),
                               std::string("--quiet")})
    a.push_back(s);
  return a;
}
}  // namespace

TEST(Fleet, SixtyFourAgentProcessesJoinAndFinish) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(base(out, {"--agents", "64", "--duration", "2"}), out, 400);
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.summary["status"], "ok");
  EXPECT_EQ(r.summary["ticks"], 200);
  // Every one of the 68 processes announced itself, ran the lock-step and ended cleanly.
  ASSERT_EQ(r.summary["processes"].size(), 68u);
  for (const auto& p : r.summary["processes"]) EXPECT_EQ(p["exit_code"].get<int>(), 0) << p.dump();
  EXPECT_EQ(r.summary["plant"]["live_agents"]["L"], 32);
  EXPECT_EQ(r.summary["plant"]["live_agents"]["R"], 32);
  EXPECT_EQ(r.summary["plant"]["declared_dead_by_deadline"], 0);
}
