// Fault tests (ctest label `faults`): real fleets, real SIGKILLs of real processes.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>

#include "tests/integration/fleet_runner.hpp"

using namespace maptr::testing;

namespace {

std::vector<std::string> run_args(const std::string& out, std::vector<std::string> extra) {
  std::vector<std::string> a = {"run"};
  a.insert(a.end(), extra.begin(), extra.end());
  for (const std::string& s : {std::string("--out"), out, std::string("--domain"), std::to_string(private_domain()),
                               std::string("--quiet")})
    a.push_back(s);
  return a;
}

const nlohmann::json* event_of(const nlohmann::json& s, const std::string& name, const std::string& what) {
  for (const auto& e : s["plant"]["membership_events"])
    if (e["name"] == name && e["event"] == what) return &e;
  return nullptr;
}

}  // namespace

TEST(Faults, KilledActiveAgentsAreReplacedAndTheSpeedRecovers) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  // Energy-conscious: Level 3 starts with the least-worn agents, L0, L1, ... By killing L0, L1
  // and L2 at least one active agent dies.
  auto r = run_cli(run_args(out, {"--duration", "24", "--kill", "L0@12", "--kill", "L1@12", "--kill", "L2@12"}), out, 300);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto& s = r.summary;
  EXPECT_EQ(s["status"], "ok");
  ASSERT_EQ(s["failures"].size(), 3u);
  for (const auto& f : s["failures"]) {
    ASSERT_FALSE(f["detected_s"].is_null()) << f.dump();
    EXPECT_LT(f["detect_wall_ms"].get<double>(), 1000.0) << "the launcher sees its child die at once: " << f.dump();
    EXPECT_FALSE(f["recovered_s"].is_null()) << f.dump();
    EXPECT_LT(f["max_speed_error_pct"].get<double>(), 10.0) << f.dump();
  }
  EXPECT_NE(event_of(s, "L0", "died (launcher)"), nullptr);
  // Replaced: both sides run the same count at the end although L lost three agents.
  EXPECT_EQ(s["active_agents"]["L"], s["active_agents"]["R"]);
  EXPECT_EQ(s["plant"]["live_agents"]["L"], 5);
  EXPECT_NEAR(s["plant"]["final_speed_mps"].get<double>(), 10.0, 0.2);
  // The killed agents' process records say so; everyone else ended cleanly.
  for (const auto& p : s["processes"]) {
    const std::string n = p["name"];
    if (n == "L0" || n == "L1" || n == "L2")
      EXPECT_EQ(p["signal"], 9) << p.dump();
    else
      EXPECT_EQ(p["exit_code"], 0) << p.dump();
  }
}

TEST(Faults, ASideWithoutLiveAgentsDegradesAndSaysWhy) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(run_args(out, {"--agents", "8", "--mode", "all", "--duration", "10", "--kill", "L0@4", "--kill",
                                  "L1@4", "--kill", "L2@4", "--kill", "L3@4"}),
                   out, 240);
  EXPECT_EQ(r.exit_code, 3) << r.output;  // degraded
  const std::string status = r.summary["status"];
  EXPECT_EQ(status.rfind("degraded: side L has no live agent", 0), 0u) << status;
  EXPECT_EQ(r.summary["plant"]["live_agents"]["L"], 0);
  EXPECT_EQ(r.summary["active_agents"]["L"], 0);
}

TEST(Faults, RestartedGroupControllerContinuesItsWearLedger) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(run_args(out, {"--duration", "40", "--kill", "group-L@10", "--restart", "group-L@11"}), out, 300);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The restarted controller loaded the ledger it had saved, and went on counting.
  std::ifstream log(out + "/logs/group-L.log");
  std::string line, resumed;
  while (std::getline(log, line))
    if (line.find("resumed the wear ledger:") != std::string::npos) resumed = line;
  ASSERT_FALSE(resumed.empty());
  const auto pos = resumed.find("ledger: ") + 8;
  const int decisions_at_restart = std::stoi(resumed.substr(pos));
  EXPECT_GT(decisions_at_restart, 0);
  const auto ledger = read_json(out + "/ledger-L.json");
  EXPECT_GT(ledger["decisions"].get<int>(), decisions_at_restart);
  double wear = 0.0;
  for (double w : ledger["wear_m"].get<std::vector<double>>()) wear += w;
  EXPECT_GT(wear, 100.0);  // more than the first 10 s could give one active set
  for (const auto& p : r.summary["processes"])
    if (p["name"] == "group-L") EXPECT_EQ(p["starts"], 2);
  EXPECT_NE(event_of(r.summary, "group-L", "rejoined"), nullptr);
}

TEST(Faults, KillingTheLauncherLeavesNoProcessBehind) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  const pid_t launcher = start_cli(run_args(out, {"--duration", "600"}), tmp.path() + "/out.log");
  ASSERT_TRUE(wait_for([&] { return count_lines(out + "/trace.csv") > 100; }, 120)) << "the run did not start";
  const auto fleet = read_json(out + "/fleet.json");
  std::vector<pid_t> pids;
  for (const auto& p : fleet["processes"]) pids.push_back(p["pid"].get<int>());
  ASSERT_EQ(pids.size(), 20u);
  for (pid_t p : pids) ASSERT_TRUE(process_running(p)) << p;
  kill(launcher, SIGKILL);
  waitpid(launcher, nullptr, 0);
  EXPECT_TRUE(wait_for(
      [&] {
        for (pid_t p : pids)
          if (process_running(p)) return false;
        return true;
      },
      10))
      << "a fleet process outlived its launcher";
}

TEST(Faults, AnAgentStartedOutsideTheLauncherIsDetectedByLiveliness) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  const pid_t launcher = start_cli(run_args(out, {"--duration", "20", "--external", "L3"}), tmp.path() + "/out.log");
  ASSERT_TRUE(wait_for([&] { return !read_json(out + "/fleet.json").is_null(); }, 60));
  const auto fleet = read_json(out + "/fleet.json");
  // Start L3 by hand, as a user on another terminal would.
  const pid_t agent = fork();
  if (agent == 0) {
    setenv("MAPTR_DOMAIN", std::to_string(fleet["domain"].get<int>()).c_str(), 1);
    setenv("MAPTR_DISCOVERY_SERVER", fleet["discovery_server"].get<std::string>().c_str(), 1);
    setenv("MAPTR_LEASE_S", std::to_string(fleet["lease_s"].get<double>()).c_str(), 1);
    for (const auto& p : fleet["processes"])
      if (p["name"] == "L3") setenv("MAPTR_PARTICIPANT_ID", std::to_string(p["participant_id"].get<int>()).c_str(), 1);
    const std::string bin = std::string(MAPTR_BIN_DIR) + "/maptr_agent";
    const std::string cfg = fleet["config"], dir = fleet["run_dir"];
    execl(bin.c_str(), bin.c_str(), "--id", "L3", "--config", cfg.c_str(), "--run-dir", dir.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  ASSERT_TRUE(wait_for([&] { return count_lines(out + "/trace.csv") > 500; }, 120)) << "the run did not start";
  kill(agent, SIGKILL);
  waitpid(agent, nullptr, 0);
  const int code = wait_child(launcher, 240);
  EXPECT_EQ(code, 0);
  const auto s = read_json(out + "/summary.json");
  // The launcher could not see it die: DDS liveliness did.
  const auto* e = event_of(s, "L3", "lost (DDS liveliness)");
  ASSERT_NE(e, nullptr) << s["plant"]["membership_events"].dump();
  EXPECT_GT((*e)["t_s"].get<double>(), 4.9);
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["plant"]["live_agents"]["L"], 7);
}

TEST(Faults, ChaosRunWithAFixedSeedEndsWithoutACrash) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(run_args(out, {"--duration", "30", "--chaos", "7"}), out, 400);
  ASSERT_FALSE(r.timed_out) << r.output;
  const std::string status = r.summary["status"];
  EXPECT_TRUE(status == "ok" || status.rfind("degraded", 0) == 0) << status;
  EXPECT_EQ(r.summary["chaos_seed"], 7);
  EXPECT_GE(r.summary["failures"].size(), 2u);
  std::set<std::string> killed;
  for (const auto& f : r.summary["failures"]) {
    if (f["action"] == "kill") killed.insert(f["target"].get<std::string>());
    // A process restarted with time to spare joins the lock-step again (fresh DDS ports).
    if (f["action"] == "restart" && f["at_s"].get<double>() < 22.0)
      EXPECT_FALSE(f["detected_s"].is_null()) << "did not rejoin: " << f.dump();
  }
  for (const auto& p : r.summary["processes"]) {
    // A process either ended cleanly or was SIGKILLed by the schedule: no crash, no abort.
    if (p["exit_code"] != 0) {
      EXPECT_EQ(p["signal"], 9) << p.dump();
      EXPECT_TRUE(killed.count(p["name"].get<std::string>())) << p.dump();
    }
  }
}
