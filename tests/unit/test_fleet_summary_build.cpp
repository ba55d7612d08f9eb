// The launcher's children and the run summary (deploy/fleet/children.hpp, summary_build.hpp).
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <thread>

#include "deploy/fleet/children.hpp"
#include "deploy/fleet/summary_build.hpp"
#include "tests/unit/unit_temp_dir.hpp"

using namespace maptr::deploy::fleet;

namespace {
Child plant_child(int exit_code, int signal) {
  Child c;
  c.name = "plant";
  c.exit_code = exit_code;
  c.signal = signal;
  return c;
}

/// Runs /bin/sh -c script as a child and reaps it.
Child run_shell(const std::string& script, const std::string& dir) {
  Child c;
  c.name = "sh";
  c.binary = "/bin/sh";
  c.args = {"-c", script};
  std::filesystem::create_directories(dir + "/logs");
  spawn(c, dir, {{"FLEET_TEST", "42"}}, 7);
  EXPECT_TRUE(c.running);
  for (;;) {
    const auto e = reap_one();
    if (e && e->pid == c.pid) {
      record_exit(c, *e);
      return c;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}
}  // namespace

/// The plant's results as plant.json would give them.
std::optional<maptr::records::PlantResults> results(const nlohmann::json& j) {
  return maptr::records::plant_results_from_json(j, "plant.json");
}

TEST(FleetSummary, StatusRules) {
  const auto plant = results({{"status", "ok"}, {"sim_time_s", 10.0}});
  EXPECT_EQ(final_status("ok", plant, plant_child(0, 0)), "ok");
  EXPECT_EQ(final_status("ok", results({{"status", "degraded: L"}}), plant_child(0, 0)), "degraded: L");
  EXPECT_EQ(final_status("ok", results({{"ticks", 3}}), plant_child(0, 0)), "unknown");
  EXPECT_EQ(final_status("ok", std::nullopt, plant_child(-1, 9)),
            "aborted: the plant ended without results (exit -1, signal 9)");
  EXPECT_EQ(final_status("aborted: interrupted", plant, plant_child(0, 0)), "aborted: interrupted");
}

TEST(FleetSummary, ExitCodeAndSignalOfChildren) {
  const maptr::testing::UnitTempDir tmp("fleet_children");
  const std::string dir = tmp.path();
  const Child ok = run_shell("exit 0", dir);
  EXPECT_EQ(ok.exit_code, 0);
  EXPECT_EQ(ok.signal, 0);
  EXPECT_TRUE(ended_cleanly(ok));
  EXPECT_GT(ok.max_rss_kB, 0);
  const Child three = run_shell("exit 3", dir);
  EXPECT_EQ(three.exit_code, 3);
  EXPECT_FALSE(ended_cleanly(three));
  const Child killed = run_shell("kill -9 $$", dir);
  EXPECT_EQ(killed.exit_code, -1);
  EXPECT_EQ(killed.signal, SIGKILL);
  EXPECT_FALSE(ended_cleanly(killed));
  // The environment and the log of a child.
  const Child env = run_shell("echo \"$FLEET_TEST $MAPTR_PARTICIPANT_ID\"", dir);
  std::ifstream log(dir + "/logs/sh.stderr");
  std::string all((std::istreambuf_iterator<char>(log)), {});
  EXPECT_NE(all.find("42 7"), std::string::npos) << all;
  const auto procs = processes_json({ok, three, killed});
  ASSERT_EQ(procs.size(), 3u);
  EXPECT_EQ(procs[1]["exit_code"], 3);
  EXPECT_EQ(procs[2]["signal"], SIGKILL);
  EXPECT_EQ(procs[0]["starts"], 1);
  EXPECT_EQ(procs[0]["external"], false);
}

TEST(FleetSummary, AnEndIsDescribedWithTheLastCriticalOrErrorLineOfTheLog) {
  const maptr::testing::UnitTempDir tmp("fleet_describe_end");
  const std::string dir = tmp.path();
  std::filesystem::create_directories(dir + "/logs");
  {
    std::ofstream log(dir + "/logs/group-L.log");
    log << "2026-11-25 01:28:06.183 [group-L] info: ledger saved\n"
        << "2026-11-25 01:28:13.455 [group-L] error: first problem\n"
        << "2026-11-25 01:28:13.455 [group-L] critical: wear ledger L.json has 8 agents, the scenario 64\n"
        << "2026-11-25 01:28:13.456 [group-L] info: bye\n";
  }
  Child group = plant_child(1, 0);
  group.name = "group-L";
  EXPECT_EQ(describe_end(group, dir), "group-L exited 1: wear ledger L.json has 8 agents, the scenario 64");
  Child agent = plant_child(-1, SIGKILL);
  agent.name = "L3";  // no log at all
  EXPECT_EQ(describe_end(agent, dir), "L3 was killed by signal 9");
}

TEST(FleetSummary, ParticipantIdsCycleThroughWindows) {
  ParticipantIds ids(10, 3);
  EXPECT_EQ(ids.take(2, 0), 2);
  EXPECT_EQ(ids.take(2, 1), 12);
  EXPECT_EQ(ids.take(2, 2), 22);
  EXPECT_EQ(ids.take(2, 3), 2);
  EXPECT_EQ(ids.highest(), 22);
}

TEST(FleetSummary, SummaryOfARunFromItsFiles) {
  const maptr::testing::UnitTempDir tmp("fleet_summary");
  const std::string dir = tmp.path();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/plant.json") << R"({"status":"ok","sim_time_s":20.0,"ticks":2000,"distance_m":10.0,
      "energy_J":500.0,"mean_active_agents":5.5,"membership_events":[]})";
  std::ofstream(dir + "/level2-L.csv")
      << "t_s,n_live,n_other,status,relaxed,ipopt_n_active,oracle_n_active,n_target,solve_ms\n"
      << "1,8,8,1,3.2,4,4,4,2.0\n1,8,8,1,3.2,4,3,4,4.0\n1,8,8,2,9,8,-1,8,6.0\n";
  maptr::config::Scenario sc;
  sc.source = "/project/deploy/scenarios/default.yaml";
  RunRecord r;
  r.run_wall_s = 4.0;
  r.discovery_s = 1.5;
  r.transport = "shm";
  const nlohmann::json s = build_summary(sc, "/project", r, dir, {plant_child(0, 0)});
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["scenario_file"], "deploy/scenarios/default.yaml");
  EXPECT_DOUBLE_EQ(s["real_time_factor"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(s["mileage_m_per_J"].get<double>(), 0.02);
  EXPECT_EQ(s["trace_sha256"], "");
  EXPECT_FALSE(s.contains("chaos_seed"));
  const auto& l2 = s["level2"]["L"];
  EXPECT_EQ(l2["decisions"], 3);
  EXPECT_EQ(l2["infeasible"], 1);
  EXPECT_EQ(l2["oracle_checked"], 2);
  EXPECT_EQ(l2["oracle_differs"], 1);
  EXPECT_DOUBLE_EQ(l2["solve_ms_median"].get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(l2["solve_ms_max"].get<double>(), 6.0);
  EXPECT_FALSE(s["level2"].contains("R"));
  const std::string human = maptr::deploy::human_summary(s);
  EXPECT_NE(human.find("status      ok"), std::string::npos) << human;
  EXPECT_NE(human.find("oracle differed 1 of 2"), std::string::npos) << human;
}

TEST(FleetSummary, RejectedSamplesByProcessKindAndReadiness) {
  const maptr::testing::UnitTempDir tmp("fleet_summary_rejects");
  const std::string dir = tmp.path();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/plant.json") << R"({"status":"ok","rejected_by_process":{"plant":7,"L0":2},
      "rejected_by_kind":{"forged":4,"undecodable":3},"membership_events":[]})";
  maptr::config::Scenario sc;
  RunRecord r;
  r.launcher_rejected = 9;
  r.ready_rejected = {{"forged", 6}};
  r.launcher_by_kind = {{"forged", 8}, {"undecodable", 1}};
  const nlohmann::json s = build_summary(sc, "/project", r, dir, {plant_child(0, 0)});
  EXPECT_EQ(s["rejected_samples"]["plant"], 7);
  EXPECT_EQ(s["rejected_samples"]["L0"], 2);
  EXPECT_EQ(s["rejected_samples"]["launcher"], 9);
  EXPECT_EQ(s["rejected_ready"]["forged"], 6);
  EXPECT_EQ(s["rejected_ready"]["stale"], 0);  // every kind is there, even at 0
  EXPECT_EQ(s["rejected_ready"]["malformed"], 0);
  EXPECT_EQ(s["rejected_by_kind"]["plant"]["undecodable"], 3);
  EXPECT_EQ(s["rejected_by_kind"]["launcher"]["forged"], 8);
}

TEST(FleetSummary, ABrokenLevel2LogIsReportedWithoutDecisions) {
  const maptr::testing::UnitTempDir tmp("fleet_summary_broken_l2");
  const std::string dir = tmp.path();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/level2-L.csv") << "t_s,n_live,status\n1,8,1\n";  // columns missing
  std::ofstream(dir + "/level2-R.csv")
      << "t_s,n_live,n_other,status,relaxed,ipopt_n_active,oracle_n_active,n_target,solve_ms\n"
      << "1,8,8,1,3.2,4,-1,4,2.5\n";
  const nlohmann::json l2 = level2_stats(dir);
  EXPECT_EQ(l2["L"]["decisions"], 0);
  EXPECT_NE(l2["L"]["error"].get<std::string>().find("n_other"), std::string::npos) << l2.dump();
  EXPECT_FALSE(l2["L"].contains("solve_ms_median"));
  EXPECT_EQ(l2["R"]["decisions"], 1);
  EXPECT_EQ(l2["R"]["oracle_checked"], 0);  // the oracle did not run (-1)
  EXPECT_DOUBLE_EQ(l2["R"]["solve_ms_median"].get<double>(), 2.5);
  EXPECT_FALSE(l2["R"].contains("error"));
}

namespace {

TEST(FleetSummary, ARecordingWithFewerAnswersThanThePlantUsedIsIncompleteAndSaidSo) {
  const auto plant = results(
      {{"answers_taken", {{"maptr/agent_reply", 512000}, {"maptr/group", 2000}, {"maptr/central", 1000}}}});
  // What a recording of the 512-agent fleet held once: most answers missing, the rest there;
  // repeated answers make the recorder's counts higher than the plant's.
  const std::map<std::string, uint64_t> recorded = {
      {"maptr/agent_reply", 32967}, {"maptr/group", 2004}, {"maptr/central", 1000}, {"maptr/tick", 1001}};
  const nlohmann::json c = recording_check(recorded, plant);
  ASSERT_TRUE(c.is_object());
  EXPECT_EQ(c["recorded"]["maptr/tick"], 1001);
  ASSERT_EQ(c["incomplete"].size(), 1u) << c.dump();
  EXPECT_EQ(c["incomplete"]["maptr/agent_reply"]["recorded"], 32967);
  EXPECT_EQ(c["incomplete"]["maptr/agent_reply"]["taken_by_plant"], 512000);
  nlohmann::json s = {{"status", "ok"}, {"processes", nlohmann::json::array()},
                      {"battery_discharge_mAh", {{"L", 1.0}, {"R", 1.0}}}, {"recording", c}};
  const std::string human = maptr::deploy::human_summary(s);
  EXPECT_NE(human.find("run.mcap INCOMPLETE: maptr/agent_reply holds 32967 messages, the plant used 512000"),
            std::string::npos)
      << human;
  // A complete recording, a topic the recording leaves out (record: plant), and none at all.
  EXPECT_TRUE(recording_check({{"maptr/agent_reply", 512000}, {"maptr/tick", 1001}}, plant)["incomplete"].empty());
  EXPECT_TRUE(recording_check({}, plant).is_null());
  // The run does not end ok with it: an ok run becomes degraded and says what is missing; a
  // status that is already not ok stays as it is; a complete recording or none leaves ok.
  EXPECT_EQ(recording_status("ok", c),
            "degraded: run.mcap incomplete: maptr/agent_reply holds 32967 of the 512000 samples the plant used");
  EXPECT_EQ(recording_status("aborted: stop signal", c), "aborted: stop signal");
  EXPECT_EQ(recording_status("ok", recording_check({{"maptr/agent_reply", 512000}}, plant)), "ok");
  EXPECT_EQ(recording_status("ok", nullptr), "ok");
}

}  // namespace
