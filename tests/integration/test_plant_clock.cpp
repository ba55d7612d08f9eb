// The launcher follows the plant's participant only (ctest label `faults`): another
// participant publishing ticks and fault gates into a running fleet moves neither the
// launcher's clock nor its faults.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/integration/fleet_runner.hpp"

using namespace maptr::testing;

namespace {
constexpr double kForgedT = 1000.0;  // simulated time the forger claims, s

pid_t start_forger(const nlohmann::json& fleet, double seconds) {
  const pid_t pid = fork();
  if (pid == 0) {
    setenv("MAPTR_DOMAIN", std::to_string(fleet["domain"].get<int>()).c_str(), 1);
    setenv("MAPTR_DISCOVERY_SERVER", fleet["discovery_server"].get<std::string>().c_str(), 1);
    setenv("MAPTR_LEASE_S", std::to_string(fleet["lease_s"].get<double>()).c_str(), 1);
    // The launcher's participant id in the second id window: it never restarts, so it is free.
    const int stride = static_cast<int>(fleet["processes"].size()) + 2;
    setenv("MAPTR_PARTICIPANT_ID", std::to_string(stride + 1).c_str(), 1);
    const std::string bin = std::string(MAPTR_BIN_DIR) + "/maptr_forge_tick";
    const std::string secs = std::to_string(seconds), t = std::to_string(kForgedT);
    execl(bin.c_str(), bin.c_str(), secs.c_str(), t.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}
}  // namespace

TEST(Faults, ForgedTicksAndGatesMoveNeitherTheLaunchersClockNorItsFaults) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  // A scheduled kill late in the run: a forged gate at t = 1000 s must not bring it forward.
  const pid_t launcher = start_cli(run_args(out, {"--duration", "12", "--realtime", "--kill", "R2@10"}),
                                   tmp.path() + "/out.log");
  ASSERT_TRUE(wait_for([&] { return count_lines(out + "/trace.csv") > 200; }, 120))
      << "the run did not start";
  const pid_t forger = start_forger(read_json(out + "/fleet.json"), 4.0);
  ASSERT_TRUE(wait_for([&] { return count_lines(out + "/trace.csv") > 500; }, 60));
  // A command acts at the launcher's current simulated time.
  { std::ofstream(out + "/control") << "kill L1\n"; }
  EXPECT_EQ(wait_child(forger, 30), 0);
  const int code = wait_child(launcher, 240);
  const auto s = read_json(out + "/summary.json");
  // On a failure, what the run said of itself.
  std::ifstream said(tmp.path() + "/out.log");
  std::stringstream output;
  output << said.rdbuf();
  ASSERT_EQ(code, 0) << "status: " << s.value("status", std::string("(no summary)")) << "\n" << output.str();
  ASSERT_EQ(s["failures"].size(), 2u) << s["failures"].dump();
  for (const auto& f : s["failures"]) {
    EXPECT_LT(f["at_s"].get<double>(), 12.0) << f.dump();
    if (f["target"] == "R2") {
      EXPECT_NEAR(f["at_s"].get<double>(), 10.0, 0.011) << f.dump();
    }
    if (f["target"] == "L1") {
      EXPECT_GT(f["at_s"].get<double>(), 4.0) << f.dump();
    }
  }
  std::ifstream log(out + "/logs/launcher.log");
  std::stringstream text;
  text << log.rdbuf();
  EXPECT_NE(text.str().find("from a participant other than the plant's"), std::string::npos);
}
