// Fault tests (ctest label `faults`): real fleets, real SIGKILLs of real processes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <tuple>

#include "records/trace.hpp"
#include "tests/hooks/hooks.hpp"
#include "tests/integration/fleet_runner.hpp"

using namespace maptr::testing;

namespace {

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
  // The restarted controller went on from the ledger the plant kept from its predecessor's last
  // status (handed to it in its first tick: no file), and went on counting.
  std::ifstream log(out + "/logs/group-L.log");
  std::string line, resumed;
  while (std::getline(log, line))
    if (line.find("resumed the wear ledger the plant kept:") != std::string::npos) resumed = line;
  ASSERT_FALSE(resumed.empty());
  const auto pos = resumed.find("kept: ") + 6;
  const int decisions_at_restart = std::stoi(resumed.substr(pos));
  EXPECT_GT(decisions_at_restart, 0);
  const auto ledger = read_json(out + "/ledger-L.json");
  EXPECT_GT(ledger["decisions"].get<int>(), decisions_at_restart);
  double wear = 0.0;
  for (double w : ledger["wear_m"].get<std::vector<double>>()) wear += w;
  EXPECT_GT(wear, 100.0);  // more than the first 10 s could give one active set
  EXPECT_EQ(r.summary["plant"]["group_wear"]["L"]["regressions"], 0);  // not one metre lost
  for (const auto& p : r.summary["processes"])
    if (p["name"] == "group-L") {
      EXPECT_EQ(p["starts"], 2);
    }
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
  pids.push_back(fleet["discovery_server_pid"].get<int>());  // the discovery server goes too
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

TEST(Faults, KilledDiscoveryServerIsRestartedAndAnAgentStartedAfterwardsRejoins) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(run_args(out, {"--duration", "20", "--kill", "discovery@3", "--kill", "L0@4", "--restart", "L0@5"}),
                   out, 300);
  ASSERT_FALSE(r.timed_out) << r.output;
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.summary["status"], "ok");
  EXPECT_EQ(r.summary["discovery_server_restarts"], 1);
  // The restarted L0 can only be found through the restarted server. The plant holds the
  // restart's tick until L0 is matched and ready, so it rejoins at that very tick, whatever the
  // machine's speed.
  const auto* e = event_of(r.summary, "L0", "rejoined");
  ASSERT_NE(e, nullptr) << r.summary["plant"]["membership_events"].dump();
  EXPECT_DOUBLE_EQ((*e)["t_s"].get<double>(), 5.0);
  EXPECT_EQ(r.summary["plant"]["live_agents"]["L"], 8);
}

TEST(Faults, AnAgentStartedOutsideTheLauncherIsDetectedByLiveliness) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  // Liveliness is wall-clock time: --realtime keeps the 20 simulated seconds at least 20 s long,
  // so the lease expires inside the run on a fast machine too.
  const pid_t launcher =
      start_cli(run_args(out, {"--duration", "20", "--realtime", "--external", "L3"}), tmp.path() + "/out.log");
  ASSERT_TRUE(wait_for([&] { return !read_json(out + "/fleet.json").is_null(); }, 60));
  const auto fleet = read_json(out + "/fleet.json");
  // Start L3 by hand, as a user on another terminal would.
  const pid_t agent = fork();
  if (agent == 0) {
    setenv("MAPTR_DOMAIN", std::to_string(fleet["domain"].get<int>()).c_str(), 1);
    setenv("MAPTR_DISCOVERY_SERVER", fleet["discovery_server"].get<std::string>().c_str(), 1);
    setenv("MAPTR_LEASE_S", std::to_string(fleet["lease_s"].get<double>()).c_str(), 1);
    setenv("MAPTR_FLEET_ID", std::to_string(fleet["fleet_id"].get<uint32_t>()).c_str(), 1);
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
  ASSERT_EQ(code, 0);
  const auto s = read_json(out + "/summary.json");
  // The launcher could not see it die: DDS liveliness did.
  const auto* e = event_of(s, "L3", "lost (DDS liveliness)");
  ASSERT_NE(e, nullptr) << s["plant"]["membership_events"].dump();
  EXPECT_GT((*e)["t_s"].get<double>(), 4.9);
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["plant"]["live_agents"]["L"], 7);
  // Its pid was taken only after the launcher checked it (its binary, this fleet's id and its
  // participant id in its environment): the one the test started.
  for (const auto& p : s["processes"])
    if (p["name"] == "L3") EXPECT_EQ(p["pid"].get<pid_t>(), agent) << p.dump();
  EXPECT_EQ(s["rejected_ready"]["forged"], 0);
}

TEST(Faults, ChaosRunWithAFixedSeedEndsWithoutACrash) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(run_args(out, {"--duration", "30", "--chaos", "7"}), out, 400);
  ASSERT_FALSE(r.timed_out) << r.output;
  // ok (0) or degraded (3); anything else may have no summary.
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 3) << "exit " << r.exit_code << "\n" << r.output;
  const std::string status = r.summary["status"];
  EXPECT_TRUE(status == "ok" || status.rfind("degraded", 0) == 0) << status;
  EXPECT_EQ(r.summary["chaos_seed"], 7);
  EXPECT_GE(r.summary["failures"].size(), 2u);
  std::set<std::string> killed;
  for (const auto& f : r.summary["failures"]) {
    if (f["action"] == "kill") killed.insert(f["target"].get<std::string>());
    // A process restarted with time to spare joins the lock-step again (fresh DDS ports).
    if (f["action"] == "restart" && f["at_s"].get<double>() < 22.0) {
      EXPECT_FALSE(f["detected_s"].is_null()) << "did not rejoin: " << f.dump();
    }
  }
  for (const auto& p : r.summary["processes"]) {
    // A process either ended cleanly or was SIGKILLed by the schedule: no crash, no abort.
    if (p["exit_code"] != 0) {
      EXPECT_EQ(p["signal"], 9) << p.dump();
      EXPECT_TRUE(killed.count(p["name"].get<std::string>())) << p.dump();
    }
  }
}

TEST(Faults, KilledCentralMakesTheAgentsStopSafelyAndARestartedOneResumes) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  // Central silent for more than control.central_timeout_s (1 s): agents ramp their reference
  // to zero at 2 m/s^2, so their voltage drops to 0 and the robot coasts (the driver cannot
  // brake: it only slows by friction and drag); the restarted central brings the speed back.
  auto r = run_cli(run_args(out, {"--mode", "all", "--duration", "30", "--kill", "central@10", "--restart",
                                  "central@16"}),
                   out, 300);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  double v_min_outage = 1e9, volt_min_outage = 1e9, v_end = 0;
  for (const auto& row : maptr::records::read_trace(out + "/trace.csv")) {
    if (row.t_s > 12.0 && row.t_s < 16.0) {
      v_min_outage = std::min(v_min_outage, row.v_x_mps);
      volt_min_outage = std::min(volt_min_outage, row.V_L_mean_V);
    }
    v_end = row.v_x_mps;
  }
  EXPECT_LT(volt_min_outage, 0.01) << "the agents kept driving without central";
  EXPECT_LT(v_min_outage, 9.8) << "the robot did not slow down without central";
  EXPECT_NEAR(v_end, 10.0, 0.3) << "the restarted central did not bring the speed back";
  EXPECT_NE(event_of(r.summary, "central", "rejoined"), nullptr);
}

TEST(Faults, ACentralKilledForGoodDegradesTheRunAndSaysWhy) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  // Without central the agents ramp their reference to zero and the robot coasts: it slows
  // only by friction, so 2 s after the kill the speed alone is still within the 5 % band (the
  // status was "ok" before the plant looked at its controllers).
  auto r = run_cli(run_args(out, {"--duration", "14", "--kill", "central@12"}), out, 300);
  ASSERT_FALSE(r.timed_out) << r.output;
  const std::string status = r.summary["status"];
  EXPECT_EQ(status, "degraded: central dead or paused at the end; its agents ran on their own safe behaviour");
  EXPECT_NE(r.output.find("central dead or paused at the end"), std::string::npos) << r.output;
}

TEST(Faults, KilledPlantEndsTheRunWithAClearErrorAndKeepsTheTrace) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(run_args(out, {"--duration", "30", "--kill", "plant@5"}), out, 300);
  EXPECT_EQ(r.exit_code, 1) << r.output;  // aborted
  const std::string status = r.summary["status"];
  EXPECT_EQ(status.rfind("aborted: the plant ended without results", 0), 0u) << status;
  // The trace up to the kill is intact: every row complete (the reader throws on a malformed
  // one and leaves out a last line cut by the kill), times strictly increasing to ~5 s.
  std::vector<maptr::records::TraceRow> trace;
  ASSERT_NO_THROW(trace = maptr::records::read_trace(out + "/trace.csv"));
  double last_t = -1;
  int rows = 0;
  for (const auto& row : trace) {
    EXPECT_GT(row.t_s, last_t);
    last_t = row.t_s;
    ++rows;
  }
  EXPECT_GE(last_t, 4.9);
  EXPECT_GE(rows, 490);
  // Every other process ended by itself (lost the plant) or by the launcher, none crashed.
  for (const auto& p : r.summary["processes"]) {
    if (p["name"] == "plant") {
      EXPECT_EQ(p["signal"], 9);
      continue;
    }
    EXPECT_TRUE(p["signal"] == 0 || p["signal"] == 15) << p.dump();
  }
}

namespace {
/// The summary's membership event of `kind` for `process`, or nullptr.
const nlohmann::json* change_of(const nlohmann::json& s, const std::string& process,
                                const std::string& kind) {
  for (const auto& e : s["membership_events"])
    if (e["process"] == process && e["kind"] == kind) return &e;
  return nullptr;
}
}  // namespace

TEST(Faults, PausedProcessesAreOutFromTheirPauseGateAndBackAtTheirResumeGateInEveryRun) {
  TempDir tmp;
  // An agent paused for 10 simulated seconds (long enough, on most machines, for its DDS lease
  // to run out) and a group controller for 3: both rejoin at their resume gate, and the trace
  // is the same in two runs.
  const std::vector<std::string> faults = {"--agents", "8",         "--duration", "18",
                                           "--pause",  "L1@4",      "--resume",   "L1@14",
                                           "--pause",  "group-R@5", "--resume",   "group-R@8"};
  std::string hash;
  for (int run = 0; run < 2; ++run) {
    const std::string out = tmp.path() + "/run" + std::to_string(run);
    auto r = run_cli(run_args(out, faults), out, 300);
    ASSERT_FALSE(r.timed_out) << r.output;
    // group-R paused for 3 s at 10 m/s: after its 1-s hold the right side coasts while the left
    // drives at full voltage, and the robot spins about three quarters of a turn and drives on
    // across its line (it did so before the path was measured, and the run said ok). The run
    // says so now: degraded, exit 3.
    ASSERT_EQ(r.exit_code, 3) << r.output;
    const auto& s = r.summary;
    EXPECT_EQ(s["status"].get<std::string>().rfind("degraded: path not followed (max cross-track ", 0), 0u)
        << s["status"];
    EXPECT_GT(s["path"]["heading_error_max_rad"].get<double>(), 1.5);
    for (const auto& [name, paused, resumed] :
         {std::tuple<std::string, double, double>{"L1", 4.0, 14.0}, {"group-R", 5.0, 8.0}}) {
      const auto *p = change_of(s, name, "paused"), *q = change_of(s, name, "resumed"),
                 *j = change_of(s, name, "rejoined");
      ASSERT_NE(p, nullptr) << s["membership_events"].dump();
      ASSERT_NE(q, nullptr) << s["membership_events"].dump();
      ASSERT_NE(j, nullptr) << s["membership_events"].dump();
      EXPECT_NEAR((*p)["t_s"].get<double>(), paused, 0.011);
      EXPECT_NEAR((*q)["t_s"].get<double>(), resumed, 0.011);
      EXPECT_DOUBLE_EQ((*j)["t_s"].get<double>(), (*q)["t_s"].get<double>()) << "rejoins at its resume gate";
      EXPECT_EQ((*p)["cause"], "scheduled");
      EXPECT_EQ((*j)["after"], "resumed");
      EXPECT_GT((*p)["wall_ms"].get<double>(), 0.0);
      EXPECT_EQ(change_of(s, name, "lease_lost"), nullptr) << "a paused member's lease is no news";
      EXPECT_EQ(change_of(s, name, "died"), nullptr);
    }
    // Nobody was restarted: the paused processes went on and ended cleanly.
    for (const auto& p : s["processes"]) {
      EXPECT_EQ(p["exit_code"], 0) << p.dump();
      EXPECT_EQ(p["starts"], 1) << p.dump();
    }
    EXPECT_EQ(s["plant"]["live_agents"]["L"], 4);
    EXPECT_EQ(s["plant"]["group_wear"]["R"]["regressions"], 0);
    if (run == 0)
      hash = s["trace_sha256"];
    else
      EXPECT_EQ(s["trace_sha256"], hash) << "a pause and its resume act at the same tick in every run";
  }
}

namespace {

/// Runs `maptr run` with the MAPTR_TEST_SILENT_ONCE hook on `name`: its first start withholds
/// its NodeReady (and creates `marker`), so the launcher has to start it again.
CliResult run_silencing_once(const std::string& name, const std::string& marker, const std::string& out,
                             const std::vector<std::string>& extra) {
  const maptr::testing::HookedBinaries hook(maptr::test_hooks::kSilentOnceEnv, name + ":" + marker);
  return run_cli(run_args(out, extra), out, 300);
}

}  // namespace

TEST(Faults, AProcessThatNeverReportsReadyIsStartedAgainDuringDiscovery) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run", marker = tmp.path() + "/L3-silenced";
  // The first start of L3 withholds its NodeReady; the launcher sees discovery make no progress
  // and starts L3 again, which then reports ready. Nothing here races the simulation.
  auto r = run_silencing_once("L3", marker, out, {"--duration", "2"});
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.summary["status"], "ok");
  EXPECT_TRUE(std::filesystem::exists(marker)) << "the hook did not silence L3";
  EXPECT_EQ(r.summary["discovery_rematched"], nlohmann::json::array({"L3"}));
  EXPECT_TRUE(r.summary["discovery_retry"].is_null()) << r.summary["discovery_retry"].dump();
  for (const auto& p : r.summary["processes"])
    EXPECT_EQ(p["starts"].get<int>(), p["name"] == "L3" ? 2 : 1) << p.dump();
}

TEST(Faults, APlantStartedAgainDuringDiscoveryIsTheOneWhoseGatesTheLauncherOpens) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run", marker = tmp.path() + "/plant-silenced";
  // The plant's first start withholds its NodeReady, so the launcher starts it again, with the
  // next participant id of its window. The launcher must follow that plant's ticks and gates:
  // the kill at 1 s is applied at its gate, and the run is not taken for stalled.
  auto r =
      run_silencing_once("plant", marker, out, {"--duration", "2", "--kill", "L1@1", "--stall-timeout", "60"});
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.summary["status"], "ok");
  EXPECT_TRUE(std::filesystem::exists(marker)) << "the hook did not silence the plant";
  EXPECT_EQ(r.summary["discovery_rematched"], nlohmann::json::array({"plant"}));
  ASSERT_EQ(r.summary["failures"].size(), 1u);
  EXPECT_FALSE(r.summary["failures"][0].contains("skipped")) << r.summary["failures"].dump();
  std::ifstream log(out + "/logs/launcher.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_FALSE(text.empty());
  EXPECT_EQ(text.find("from a participant other than the plant's"), std::string::npos) << text;
}

TEST(Faults, TheMembersThePlantNeverMatchedStartAgainNotThePlant) {
  // The hooked plant does not count the first start of L1's answer writer, as when the
  // discovery server dropped that endpoint (seen at 512 agents): every other process, L1
  // included, is ready, and only the plant is not. Its report names L1, and the launcher starts
  // L1 again, not the plant (which would have to discover the whole fleet again).
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  const auto r = [&] {
    const maptr::testing::HookedBinaries hook(maptr::test_hooks::kPlantBlindEnv, "L1");
    return run_cli(run_args(out, {"--duration", "2"}), out, 300);
  }();
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.summary["status"], "ok");
  EXPECT_EQ(r.summary["discovery_rematched"], nlohmann::json::array({"L1"}));
  for (const auto& p : r.summary["processes"])
    EXPECT_EQ(p["starts"].get<int>(), p["name"] == "L1" ? 2 : 1) << p.dump();
  std::ifstream log(out + "/logs/launcher.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("L1 was not matched by the plant within"), std::string::npos) << text;
  std::ifstream plant_log(out + "/logs/plant.log");
  const std::string plant((std::istreambuf_iterator<char>(plant_log)), std::istreambuf_iterator<char>());
  EXPECT_NE(plant.find("agent replies 15/16 (not matched: L1)"), std::string::npos) << plant;
}

TEST(Faults, AProcessThatAbortsDuringDiscoveryIsStartedAgain) {
  // As Fast DDS's assertion StatelessWriter::matched_reader_add ended an agent of a secure,
  // loaded fleet: the first start of L2 aborts (SIGABRT) where it would report ready. The
  // launcher starts it again, as it does one that never gets ready, and the run goes on.
  TempDir tmp;
  const std::string out = tmp.path() + "/run", marker = tmp.path() + "/L2-aborted";
  const auto r = [&] {
    const maptr::testing::HookedBinaries hook(maptr::test_hooks::kAbortOnceEnv, "L2:" + marker);
    return run_cli(run_args(out, {"--duration", "2"}), out, 300);
  }();
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.summary["status"], "ok");
  EXPECT_TRUE(std::filesystem::exists(marker)) << "the hook did not abort L2";
  EXPECT_EQ(r.summary["discovery_rematched"], nlohmann::json::array({"L2"}));
  for (const auto& p : r.summary["processes"])
    EXPECT_EQ(p["starts"].get<int>(), p["name"] == "L2" ? 2 : 1) << p.dump();
  std::ifstream log(out + "/logs/launcher.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("L2 ended during discovery (L2 was killed by signal 6"), std::string::npos) << text;
}
