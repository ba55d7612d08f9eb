// Fault schedule, chaos schedule and fault analysis of the launcher (deploy/fleet/).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "deploy/fleet/fault_analysis.hpp"
#include "deploy/fleet/fault_execution.hpp"
#include "deploy/fleet/fault_schedule.hpp"
#include "records/trace.hpp"
#include "tests/unit/unit_temp_dir.hpp"

using maptr::config::FaultSpec;
using namespace maptr::deploy;
using namespace maptr::deploy::fleet;

TEST(FleetFaultSchedule, FaultsDueAtAGateInTimeOrder) {
  FaultSchedule s(
      {{"L1", "restart", 8.0}, {"L1", "kill", 5.0}, {"R0", "kill", 5.0}, {"R0", "restart", 12.0}});
  EXPECT_TRUE(s.due(4.99).empty());
  const auto at5 = s.due(5.004);  // the first tick at or after 5 s
  ASSERT_EQ(at5.size(), 2u);
  EXPECT_EQ(at5[0].target, "L1");  // equal times keep their order
  EXPECT_EQ(at5[1].target, "R0");
  EXPECT_TRUE(s.due(5.01).empty()) << "a fault is due once";
  const auto at9 = s.due(9.0);
  ASSERT_EQ(at9.size(), 1u);
  EXPECT_EQ(at9[0].action, "restart");
}

TEST(FleetFaultSchedule, FaultAfterTheEndIsRecordedAsSkipped) {
  FaultSchedule s({{"L1", "kill", 5.0}, {"L1", "restart", 99.0}});
  for (const auto& f : s.due(5.0)) s.record(f, 5.0, 1000.0, decide_fault(f, {true, false, true}));
  s.close();
  const auto& r = s.records();
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0]["target"], "L1");
  EXPECT_DOUBLE_EQ(r[0]["at_s"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(r[0]["wall_ms"].get<double>(), 1000.0);
  EXPECT_FALSE(r[0].contains("skipped"));
  EXPECT_EQ(r[1]["action"], "restart");
  EXPECT_DOUBLE_EQ(r[1]["at_s"].get<double>(), 99.0);
  EXPECT_EQ(r[1]["skipped"], "scheduled after the end of the run");
  EXPECT_FALSE(r[1].contains("wall_ms"));
}

TEST(FleetFaultSchedule, ActionDependsOnTheTargetsState) {
  EXPECT_EQ(decide_fault({"L1", "kill", 1}, {true, false, true}).kind, FaultAction::kKill);
  EXPECT_EQ(decide_fault({"L1", "restart", 1}, {true, false, false}).kind, FaultAction::kRestart);
  EXPECT_EQ(decide_fault({"L1", "kill", 1}, {true, false, false}).skipped,
            "target not in a state for this action");
  EXPECT_EQ(decide_fault({"L1", "restart", 1}, {true, false, true}).kind, FaultAction::kSkip);
  EXPECT_EQ(decide_fault({"nobody", "kill", 1}, {}).kind, FaultAction::kSkip);
  EXPECT_EQ(decide_fault({"L1", "kill", 1}, {true, true, true}).skipped,
            "an external process is not the launcher's to kill or start");
  EXPECT_EQ(decide_fault({"discovery", "kill", 1}, {true, false, true}).kind, FaultAction::kKill);
  EXPECT_EQ(decide_fault({"discovery", "restart", 1}, {true, false, false}).kind, FaultAction::kSkip);
}

TEST(FleetFaultSchedule, PauseNeedsARunningTargetAndResumeAPausedOne) {
  const TargetState running{true, false, true, false}, paused{true, false, true, true},
      dead{true, false, false, false};
  EXPECT_EQ(decide_fault({"L1", "pause", 1}, running).kind, FaultAction::kPause);
  EXPECT_EQ(decide_fault({"L1", "pause", 1}, paused).kind, FaultAction::kSkip);
  EXPECT_EQ(decide_fault({"L1", "pause", 1}, dead).kind, FaultAction::kSkip);
  EXPECT_EQ(decide_fault({"L1", "resume", 1}, paused).kind, FaultAction::kResume);
  EXPECT_EQ(decide_fault({"L1", "resume", 1}, running).kind, FaultAction::kSkip);
  EXPECT_EQ(decide_fault({"L1", "resume", 1}, dead).kind, FaultAction::kSkip);
  EXPECT_EQ(decide_fault({"L1", "kill", 1}, paused).kind,
            FaultAction::kKill);  // SIGKILL ends a stopped process
  EXPECT_EQ(decide_fault({"discovery", "pause", 1}, running).kind, FaultAction::kPause);
  EXPECT_EQ(decide_fault({"discovery", "resume", 1}, paused).kind, FaultAction::kResume);
  EXPECT_EQ(decide_fault({"L1", "pause", 1}, {true, true, true, false}).kind,
            FaultAction::kSkip);  // external
}

TEST(FleetFaultSchedule, RecordsSayWhoAskedForTheFault) {
  FaultSchedule s({{"L1", "pause", 5.0}, {"L1", "resume", 8.0}});
  for (const auto& f : s.due(5.0))
    s.record(f, 5.0, 1000.0, decide_fault(f, {true, false, true, false}), "chaos");
  for (const auto& f : s.due(8.0)) s.record(f, 8.0, 1500.0, decide_fault(f, {true, false, true, true}));
  const auto& r = s.records();
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0]["origin"], "chaos");
  EXPECT_EQ(r[1]["origin"], "scheduled");
  EXPECT_FALSE(r[1].contains("skipped"));
}

namespace {
/// Processes as the execution sees them: a state and a pid each, and what was done to them.
struct StubTargets : FaultTargets {
  std::map<std::string, TargetState> state;
  std::map<std::string, pid_t> pid;
  std::vector<std::string> done;
  TargetState state_of(const std::string& t) override { return state.count(t) ? state[t] : TargetState{}; }
  pid_t pid_of(const std::string& t) override { return pid.count(t) ? pid[t] : -1; }
  void kill_target(const std::string& t) override {
    done.push_back("kill " + t);
    state[t].running = false;
  }
  void restart_target(const std::string& t) override {
    done.push_back("restart " + t);
    state[t].running = true;
    pid[t] += 100;
  }
  void pause_target(const std::string& t, bool p) override {
    done.push_back((p ? "pause " : "resume ") + t);
    state[t].paused = p;
  }
};
}  // namespace

TEST(FleetFaultExecution, EachFaultActsOnItsTargetThroughTheRuleAndIsRecorded) {
  StubTargets t;
  t.state["L1"] = {true, false, true, false};
  t.pid["L1"] = 41;
  t.state["central"] = {true, true, true, false};  // external: the user's to end
  FaultExecution x(
      {{"L1", "kill", 5.0}, {"L1", "restart", 8.0}, {"central", "kill", 9.0}, {"R7", "pause", 9.0}}, t);
  const auto at5 = x.due(5.0);
  ASSERT_EQ(at5.size(), 1u);
  EXPECT_EQ(x.apply(at5[0], 5.0, 1.0, "scheduled").line, "fault: killed L1 (pid 41) at t=5.00 s");
  const auto at8 = x.due(8.0);
  ASSERT_EQ(at8.size(), 1u);
  EXPECT_EQ(x.apply(at8[0], 8.0, 2.0, "chaos").line, "fault: restarted L1 (pid 141) at t=8.00 s")
      << "the line names the new process";
  for (const auto& f : x.due(9.0)) {
    const FaultOutcome o = x.apply(f, 9.0, 3.0, "command");
    EXPECT_EQ(o.action.kind, FaultAction::kSkip) << f.target;
    EXPECT_TRUE(o.line.empty());
  }
  EXPECT_EQ(t.done, (std::vector<std::string>{"kill L1", "restart L1"}));
  const auto& r = x.schedule().records();
  ASSERT_EQ(r.size(), 4u);
  EXPECT_EQ(r[1]["origin"], "chaos");
  EXPECT_TRUE(r[2].contains("skipped")) << r[2].dump();
  EXPECT_TRUE(r[3].contains("skipped")) << r[3].dump();
}

TEST(FleetFaultSchedule, AProcessStartedOverSshIsKilledButNeverPaused) {
  TargetState remote{true, false, true, false, true};
  EXPECT_EQ(decide_fault({"L1", "kill", 1.0}, remote).kind, FaultAction::kKill);
  const FaultAction p = decide_fault({"L1", "pause", 1.0}, remote);
  EXPECT_EQ(p.kind, FaultAction::kSkip);
  EXPECT_NE(p.skipped.find("ssh"), std::string::npos) << p.skipped;
  remote.running = false;
  EXPECT_EQ(decide_fault({"L1", "restart", 2.0}, remote).kind, FaultAction::kRestart);
}

TEST(FleetFaultExecution, APauseAndItsResumeReachTheTarget) {
  StubTargets t;
  t.state["discovery"] = {true, false, true, false};
  t.pid["discovery"] = 7;
  FaultExecution x({{"discovery", "pause", 1.0}, {"discovery", "resume", 2.0}}, t);
  EXPECT_EQ(x.apply(x.due(1.0).at(0), 1.0, 0.0, "scheduled").line,
            "fault: paused the discovery server (pid 7) at t=1.00 s");
  EXPECT_EQ(x.apply(x.due(2.0).at(0), 2.0, 0.0, "scheduled").line,
            "fault: resumed the discovery server (pid 7) at t=2.00 s");
  EXPECT_EQ(t.done, (std::vector<std::string>{"pause discovery", "resume discovery"}));
}

TEST(FleetChaos, PausesAndTheDiscoveryServerWhenAsked) {
  maptr::config::Scenario sc;
  sc.robot.agents = 8;
  sc.duration_s = 40.0;
  ChaosOptions o;
  o.outages = 200;
  o.discovery = true;
  const auto a = chaos_schedule(3, sc, o);
  int pauses = 0, kills = 0, discovery = 0;
  std::map<std::string, int> open_pauses;
  for (const auto& f : a) {
    pauses += f.action == "pause";
    kills += f.action == "kill";
    discovery += f.target == "discovery";
    EXPECT_NE(f.target, "plant");
    // The discovery server is only killed: the launcher restarts it.
    if (f.target == "discovery") {
      EXPECT_EQ(f.action, "kill");
    }
  }
  EXPECT_GT(pauses, 0);
  EXPECT_GT(kills, 0);
  EXPECT_GT(discovery, 0);
  // Every resume follows a pause of its target: the scenario accepts the schedule.
  sc.faults = a;
  EXPECT_NO_THROW(sc.validate());
  // Only pauses when asked so (the discovery server is still killed).
  o.pause_share = 1.0;
  for (const auto& f : chaos_schedule(3, sc, o))
    EXPECT_TRUE(f.action == "pause" || f.action == "resume" || f.target == "discovery" ||
                maptr::config::is_agent_fault_action(f.action))
        << f.action;
  // Over ssh (where a pause cannot be done) the same draw has kills only, and the scenario takes it.
  {
    maptr::config::Scenario ssh = sc;
    ssh.faults.clear();
    ssh.hosts.count = 3;
    ssh.hosts.ssh = true;
    const auto kills_only = chaos_schedule(3, ssh, o);
    EXPECT_FALSE(kills_only.empty());
    for (const auto& f : kills_only) EXPECT_TRUE(f.action != "pause" && f.action != "resume") << f.action;
    ssh.faults = kills_only;
    EXPECT_NO_THROW(ssh.validate());
  }
  // Without pauses the targets and times are those of the plain schedule.
  o.pause_share = 0.0;
  o.discovery = false;
  o.outages = 6;
  const auto plain = chaos_schedule(7, sc, o), mixed = chaos_schedule(7, sc, 6);
  ASSERT_EQ(plain.size(), mixed.size());
  for (std::size_t i = 0; i < plain.size(); ++i) {
    EXPECT_EQ(plain[i].target, mixed[i].target);
    EXPECT_DOUBLE_EQ(plain[i].at_s, mixed[i].at_s);
  }
}

TEST(FleetChaos, SameSeedSameScheduleOnlyValidTargets) {
  maptr::config::Scenario sc;
  sc.robot.agents = 8;
  sc.duration_s = 40.0;
  const auto a = chaos_schedule(7, sc, 6), b = chaos_schedule(7, sc, 6);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GE(a.size(), 2u);
  std::set<std::string> valid = {"group-L", "group-R", "central"};
  for (int side = 0; side < 2; ++side)
    for (int j = 0; j < sc.robot.per_side(); ++j) valid.insert(maptr::config::agent_name(side, j));
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].target, b[i].target);
    EXPECT_EQ(a[i].action, b[i].action);
    EXPECT_DOUBLE_EQ(a[i].at_s, b[i].at_s);
    EXPECT_TRUE(valid.count(a[i].target)) << a[i].target;
    EXPECT_GE(a[i].at_s, 5.0);
    EXPECT_LE(a[i].at_s, sc.duration_s);
  }
  // Kill and restart, pause and resume, or fault and clear, in pairs, the second 2-8 s later
  // (capped at the end).
  for (std::size_t i = 0; i + 1 < a.size(); i += 2) {
    EXPECT_TRUE(a[i].action == "kill" || a[i].action == "pause" || a[i].action == "fault") << a[i].action;
    EXPECT_EQ(a[i + 1].action, a[i].action == "kill" ? "restart" : a[i].action == "fault" ? "clear" : "resume");
    EXPECT_EQ(a[i].target, a[i + 1].target);
    EXPECT_GE(a[i + 1].at_s - a[i].at_s, 2.0 - 0.01);
    EXPECT_LE(a[i + 1].at_s - a[i].at_s, 8.0 + 0.01);
  }
  const auto other = chaos_schedule(8, sc, 6);
  bool differs = other.size() != a.size();
  for (std::size_t i = 0; !differs && i < a.size(); ++i) differs = other[i].at_s != a[i].at_s;
  EXPECT_TRUE(differs) << "another seed gives another schedule";
}

namespace {
/// A trace at 10 Hz, wheel radius 0.1 m, reference 10 rad/s (1 m/s); the speed drops to
/// 0.9 m/s from t = 2.0 to t = 2.5 s (10 % error), else exact.
/// Written into `dir`; returns its path.
std::string synthetic_trace(const maptr::testing::UnitTempDir& dir) {
  const std::string path = dir.path() + "/fleet_trace.csv";
  maptr::records::TraceWriter out(path);
  for (int k = 0; k <= 50; ++k) {
    maptr::records::TraceRow row;
    row.tick = k;
    row.t_s = 0.1 * k;
    row.v_x_mps = (k >= 20 && k <= 25) ? 0.9 : 1.0;
    row.phidot_L_radps = row.phidot_R_radps = row.ref_L_radps = row.ref_R_radps = 10.0;
    out.write(row);
  }
  return path;
}
}  // namespace

TEST(FleetFaultAnalysis, DetectionAndRecoveryWithinTheBand) {
  const maptr::testing::UnitTempDir tmp("fleet_trace");
  const std::string trace = synthetic_trace(tmp);
  nlohmann::json failures =
      nlohmann::json::array({{{"target", "L1"}, {"action", "kill"}, {"at_s", 1.95}, {"wall_ms", 1000.0}},
                             {{"target", "L1"}, {"action", "restart"}, {"at_s", 4.0}, {"wall_ms", 3000.0}}});
  const nlohmann::json events =
      nlohmann::json::array({{{"name", "L1"}, {"event", "died"}, {"t_s", 2.1}, {"wall_ms", 1250.0}},
                             {{"name", "L1"}, {"event", "rejoined"}, {"t_s", 4.2}, {"wall_ms", 3100.0}}});
  analyse_faults(failures, events, trace, 0.1);
  const auto& kill = failures[0];
  EXPECT_DOUBLE_EQ(kill["detected_s"].get<double>(), 2.1);
  EXPECT_DOUBLE_EQ(kill["detect_wall_ms"].get<double>(), 250.0);
  EXPECT_NEAR(kill["max_speed_error_pct"].get<double>(), 10.0, 1e-9);
  EXPECT_NEAR(kill["recovered_s"].get<double>(), 2.6, 1e-9);  // last tick out of the band + one tick
  const auto& restart = failures[1];
  EXPECT_DOUBLE_EQ(restart["detected_s"].get<double>(), 4.2);
  EXPECT_NEAR(restart["recovered_s"].get<double>(), 4.0, 1e-9) << "it never left the band";
  EXPECT_NEAR(restart["max_speed_error_pct"].get<double>(), 0.0, 1e-9);
}

TEST(FleetFaultAnalysis, UndetectedAndUnrecoveredAreNull) {
  const maptr::testing::UnitTempDir tmp("fleet_trace");
  const std::string trace = synthetic_trace(tmp);
  nlohmann::json failures = nlohmann::json::array({{{"target", "R0"}, {"action", "kill"}, {"at_s", 2.0}}});
  analyse_faults(failures, nlohmann::json::array(), trace, 0.1, /*recovery_band_pct=*/5.0);
  EXPECT_TRUE(failures[0]["detected_s"].is_null());
  EXPECT_NEAR(failures[0]["recovered_s"].get<double>(), 2.6, 1e-9);
  // A wider band than the drop: recovered at once.
  analyse_faults(failures, nlohmann::json::array(), trace, 0.1, 20.0);
  EXPECT_NEAR(failures[0]["recovered_s"].get<double>(), 2.0, 1e-9);
  // No trace: no recovery.
  analyse_faults(failures, nlohmann::json::array(), trace + ".missing", 0.1);
  EXPECT_TRUE(failures[0]["recovered_s"].is_null());
}

TEST(FleetFaultAnalysis, ABrokenTraceLeavesTheFaultUnanalysed) {
  // A trace without the reference columns cannot give a speed error: the analysis reports no
  // recovery instead of failing the summary.
  const maptr::testing::UnitTempDir tmp("fleet_trace_broken");
  const std::string path = tmp.path() + "/fleet_trace_broken.csv";
  std::ofstream(path) << "tick,t_s,v_x_mps\n0,0.0,1.0\n1,0.1,1.0\n";
  nlohmann::json failures =
      nlohmann::json::array({{{"target", "L1"}, {"action", "kill"}, {"at_s", 0.0}, {"wall_ms", 0.0}}});
  const nlohmann::json events = nlohmann::json::array({{{"name", "L1"}, {"event", "died"}, {"t_s", 0.05}}});
  analyse_faults(failures, events, path, 0.1);
  EXPECT_DOUBLE_EQ(failures[0]["detected_s"].get<double>(), 0.05);
  EXPECT_TRUE(failures[0]["recovered_s"].is_null());
  EXPECT_DOUBLE_EQ(failures[0]["max_speed_error_pct"].get<double>(), 0.0);
}
