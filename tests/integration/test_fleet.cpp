// Integration tests: the real fleet (plant, central, two groups, N agents as processes) over
// Fast DDS on a private domain, through the `maptr run` command a user types.
#include <gtest/gtest.h>

#include <sched.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <utility>

#include "model/kinematics.hpp"
#include "records/trace.hpp"
#include "tests/integration/fleet_runner.hpp"

using maptr::testing::run_args;
using maptr::testing::run_cli;
using maptr::testing::TempDir;
using maptr::testing::write_file;

namespace {

void expect_clean_exit(const nlohmann::json& s, std::size_t processes) {
  ASSERT_EQ(s["processes"].size(), processes);
  for (const auto& p : s["processes"]) {
    EXPECT_EQ(p["exit_code"].get<int>(), 0) << p.dump();
    EXPECT_EQ(p["signal"].get<int>(), 0) << p.dump();
    EXPECT_GT(p["max_rss_kB"].get<long>(), 0) << p.dump();
  }
}

}  // namespace

TEST(Fleet, Default16AgentsReachTheReferenceSpeed) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(run_args(out, {"--duration", "10"}), out, 180);
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto& s = r.summary;
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["agents"], 16);
  EXPECT_EQ(s["ticks"], 1000);
  EXPECT_NEAR(s["sim_time_s"].get<double>(), 10.0, 1e-9);
  // Default reference: 10 m/s; after 10 s the speed is within 2% of it.
  EXPECT_NEAR(s["plant"]["final_speed_mps"].get<double>(), 10.0, 0.2);
  EXPECT_GT(s["discovery_s"].get<double>(), 0.0);
  EXPECT_GT(s["energy_J"].get<double>(), 0.0);
  EXPECT_EQ(s["trace_sha256"].get<std::string>().size(), 64u);
  for (const char* key : {"scenario", "mode", "motor", "gross_mass_kg", "wall_time_s", "tick_hz", "real_time_factor",
                          "distance_m", "mileage_m_per_J", "mean_active_agents", "active_agents",
                          "battery_discharge_mAh"})
    EXPECT_TRUE(s.contains(key)) << key;
  expect_clean_exit(s, 20);
  // The trace has one row per tick.
  EXPECT_EQ(maptr::records::read_trace(out + "/trace.csv").size(), 1000u);
}

TEST(Fleet, SameRunTwiceGivesTheSameTrace) {
  TempDir tmp;
  std::string sha[2];
  for (int i = 0; i < 2; ++i) {
    const std::string out = tmp.path() + "/run" + std::to_string(i);
    auto r = run_cli(run_args(out, {"--duration", "4"}), out, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    sha[i] = r.summary["trace_sha256"];
  }
  EXPECT_EQ(sha[0].size(), 64u);
  EXPECT_EQ(sha[0], sha[1]);
}

/// The ticks a follower handed to its node, from the line it logs at its end ("followed N ticks").
long long followed_ticks(const std::string& log_file) {
  std::ifstream in(log_file);
  std::string line;
  long long n = -1;
  const std::string key = "followed ";
  while (std::getline(in, line)) {
    const auto at = line.find(key);
    if (at != std::string::npos) n = std::stoll(line.substr(at + key.size()));
  }
  return n;
}

TEST(Fleet, TheTickFilterChangesNothingButTheTicksIdleAgentsTake) {
  // The same run with the tick filter (an idle agent takes only the ticks it answers) and
  // without: the same trace, bit for bit; with it, the agents Level 2 left idle after its
  // second decision (4.12 s) took far fewer ticks, without it every agent took every tick.
  TempDir tmp;
  std::string sha[2];
  std::vector<long long> followed[2];
  long long ticks = 0;
  for (int i = 0; i < 2; ++i) {
    const std::string out = tmp.path() + (i == 0 ? "/filtered" : "/every");
    auto r = run_cli(run_args(out, {"--duration", "10", "--tick-filter", i == 0 ? "true" : "false"}), out, 120);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    sha[i] = r.summary["trace_sha256"];
    ticks = static_cast<long long>(maptr::records::read_trace(out + "/trace.csv").size());
    for (const char* side : {"L", "R"})
      for (int j = 0; j < 8; ++j) followed[i].push_back(followed_ticks(out + "/logs/" + side + std::to_string(j) + ".log"));
  }
  EXPECT_EQ(sha[0].size(), 64u);
  EXPECT_EQ(sha[0], sha[1]);
  ASSERT_GT(ticks, 900);
  int few = 0;
  for (std::size_t a = 0; a < followed[0].size(); ++a) {
    EXPECT_GE(followed[1][a], ticks) << "agent " << a << " without the filter";
    EXPECT_GT(followed[0][a], ticks / 20) << "agent " << a << " with the filter: at least its idle slots";
    if (followed[0][a] < ticks * 4 / 5) ++few;
  }
  EXPECT_GE(few, 4) << "agents that took under 4/5 of the ticks with the filter";
}

/// Whether a process of this test's user may put a thread under SCHED_FIFO 1 here (tried in a
/// child process, which then ends).
bool realtime_allowed() {
  const pid_t pid = fork();
  if (pid == 0) {
    sched_param p{};
    p.sched_priority = 1;
    _exit(sched_setscheduler(0, SCHED_FIFO, &p) == 0 ? 0 : 1);
  }
  int st = 0;
  waitpid(pid, &st, 0);
  return WIFEXITED(st) && WEXITSTATUS(st) == 0;
}

TEST(Fleet, ThePlantsRealTimeThreadChangesNothingButItsScheduling) {
  // The plant's lock-step thread under SCHED_FIFO (plant_priority 1, the default), under normal
  // scheduling (0), and refused its priority (no CAP_SYS_NICE, no rtprio limit): the same trace
  // bit for bit; plant.json says what the thread ran under, and a refusal is said in the summary.
  TempDir tmp;
  struct Case {
    const char* name;
    std::vector<std::string> extra;
    maptr::testing::Privilege privilege;
  };
  const std::vector<Case> cases = {
      {"fifo", {"--plant-priority", "1"}, maptr::testing::Privilege::kAsIs},
      {"normal", {"--plant-priority", "0"}, maptr::testing::Privilege::kAsIs},
      {"refused", {}, maptr::testing::Privilege::kNoRealtime}};
  std::vector<std::string> sha, sched, output;
  for (const auto& c : cases) {
    const std::string out = tmp.path() + "/" + c.name;
    std::vector<std::string> extra = {"--duration", "3", "--mode", "all"};
    extra.insert(extra.end(), c.extra.begin(), c.extra.end());
    auto r = run_cli(run_args(out, extra), out, 180, c.privilege);
    ASSERT_FALSE(r.timed_out) << r.output;
    ASSERT_EQ(r.exit_code, 0) << c.name << "\n" << r.output;
    sha.push_back(r.summary["trace_sha256"]);
    sched.push_back(r.summary["plant"]["loop_scheduling"]);
    output.push_back(r.output);
  }
  EXPECT_EQ(sha[0].size(), 64u);
  EXPECT_EQ(sha[0], sha[1]);
  EXPECT_EQ(sha[0], sha[2]);
  const std::string refused = "normal (SCHED_FIFO 1 refused: ";
  if (realtime_allowed())
    EXPECT_EQ(sched[0].rfind("SCHED_FIFO 1 on CPU ", 0), 0u) << sched[0];
  else  // no privilege, no rtprio limit, or a cgroup without real-time time
    EXPECT_EQ(sched[0].rfind(refused, 0), 0u) << sched[0];
  EXPECT_EQ(sched[1], "normal");
  EXPECT_EQ(sched[2].rfind(refused, 0), 0u) << sched[2];
  EXPECT_NE(output[2].find("plant       lock-step thread " + refused), std::string::npos) << output[2];
  EXPECT_EQ(output[1].find("lock-step thread"), std::string::npos) << output[1];
}

TEST(Fleet, FourAndThirtyTwoAgents) {
  for (int n : {4, 32}) {
    TempDir tmp;
    const std::string out = tmp.path() + "/run";
    auto r = run_cli(run_args(out, {"--agents", std::to_string(n), "--duration", "3", "--mode", "all"}), out, 240);
    ASSERT_FALSE(r.timed_out) << r.output;
    ASSERT_EQ(r.exit_code, 0) << "N=" << n << "\n" << r.output;
    EXPECT_EQ(r.summary["agents"], n);
    EXPECT_EQ(r.summary["status"], "ok");
    expect_clean_exit(r.summary, n + 4);
    // Mode all: every agent drives.
    EXPECT_EQ(r.summary["active_agents"]["L"].get<int>() + r.summary["active_agents"]["R"].get<int>(), n);
  }
}

TEST(Fleet, ArcEndsAtThePoseTheKinematicsPredict) {
  TempDir tmp;
  const std::string scen = tmp.path() + "/arc.yaml";
  // A gentle arc: without reverse torque the inner side can only free-wheel, so the yaw rate
  // must stay within what lateral friction lets the outer side produce (docs/MODEL.md).
  write_file(scen,
             "name: arc\nagents: 16\nmode: all\nduration_s: 30\n"
             "trajectory:\n  segments:\n"
             "    - {type: straight, speed_mps: 5, duration_s: 6}\n"
             "    - {type: arc, speed_mps: 5, radius_m: 500, duration_s: 24}\n");
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(run_args(out, {scen}), out, 180);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // Dead-reckon the pose from the wheel speeds in the trace with the kinematics
  // (v = r (phidot_L + phidot_R)/2, w = r (phidot_R - phidot_L)/a), trapezoid rule.
  double x = 0, y = 0, th = 0, prev_v = 0, prev_w = 0, prev_t = 0;
  double px = 0, py = 0, pth = 0;
  bool first = true;
  for (const auto& row : maptr::records::read_trace(out + "/trace.csv")) {
    const auto body = maptr::model::body_from_rates({row.phidot_L_radps, row.phidot_R_radps}, 0.2, 0.035);
    const double t = row.t_s, v = body.v_x, w = body.w;
    if (!first) {
      const double dt = t - prev_t, wm = 0.5 * (w + prev_w), vm = 0.5 * (v + prev_v);
      x += vm * std::cos(th + 0.5 * wm * dt) * dt;
      y += vm * std::sin(th + 0.5 * wm * dt) * dt;
      th += wm * dt;
    }
    first = false;
    prev_v = v, prev_w = w, prev_t = t;
    px = row.x_m, py = row.y_m, pth = row.theta_rad;
  }
  // Plant pose vs kinematic dead reckoning: within 0.1% of the 80 m path and 1 mrad.
  EXPECT_NEAR(px, x, 0.08);
  EXPECT_NEAR(py, y, 0.08);
  EXPECT_NEAR(pth, th, 1e-3);
  // Central follows the path in closed loop: the heading ends on the reference turn of
  // 0.24 rad (it catches up the speed loop's lag), the yaw rate near the arc's 5 m/s / 500 m =
  // 0.01 rad/s plus the heading loop's correction, and the robot stays on its path.
  EXPECT_NEAR(pth, 0.24, 0.05);
  EXPECT_NEAR(prev_w, 0.01, 0.01);
  EXPECT_GT(py, 0.5);  // it turned left
  EXPECT_LT(r.summary["path"]["cross_track_max_m"].get<double>(), 0.5);
}

TEST(Fleet, BadScenariosAreRefusedBeforeAnyProcessStarts) {
  TempDir tmp;
  struct Case {
    const char* yaml;
    const char* field;
    const char* value;
  } cases[] = {
      {"agents: 16\ncolour: red\n", "colour", "red"},
      {"agents: sixteen\n", "agents", "sixteen"},
      {"gross_mass_kg: -3\n", "gross_mass_kg", "-3"},
      {"agents: 18\n", "agents", "18"},
      {"motor: X\n", "motor", "X"},
      {"trajectory:\n  segments:\n    - {type: straight, speed_mps: 40, duration_s: 5}\n", "speed_mps", "40"},
      {"trajectory:\n  segments: []\n", "trajectory.segments", "[]"},
      {"", "(top level)", "(empty)"},
      {"agents: 16\nagents: 32\n", "agents", "32"},
      {"control:\n  stop_decel_mps2: .inf\n", "control.stop_decel_mps2", ".inf"},
      {"name: ../outside\n", "name", "../outside"},
      {"faults:\n  - {target: L3, action: fault, mode: melted, at_s: 20}\n", "faults[0].mode", "melted"},
      {"faults:\n  - {target: central, action: fault, mode: open, at_s: 20}\n", "faults[0].target", "central"},
      {"faults:\n  - {target: L3, action: fault, mode: torque, value: -1, at_s: 20}\n", "faults[0].value", "-1"},
      {"faults:\n  - {target: L3, action: kill, mode: open, at_s: 20}\n", "faults[0].mode", "open"},
      {nullptr, "(file)", "not a regular file"},  // a directory given as the scenario
  };
  int i = 0;
  for (const auto& c : cases) {
    const std::string scen = tmp.path() + "/bad" + std::to_string(i++) + ".yaml";
    if (c.yaml)
      write_file(scen, c.yaml);
    else
      std::filesystem::create_directory(scen);
    const std::string out = tmp.path() + "/run" + std::to_string(i);
    auto r = run_cli(run_args(out, {scen}), out, 30);
    EXPECT_EQ(r.exit_code, 2) << c.yaml << r.output;
    EXPECT_NE(r.output.find(scen), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.field), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.value), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << "a refused scenario must not start a run";
  }
}

TEST(Fleet, BadCommandLineValuesAreRefusedLikeScenarioFields) {
  TempDir tmp;
  struct Case {
    std::vector<std::string> args;
    const char* field;
    const char* value;
  } cases[] = {
      {{"--speed", "-5"}, "speed_mps", "-5"},
      {{"--speed", "nan"}, "speed_mps", "nan"},
      {{"--gross-kg", "inf"}, "gross_mass_kg", "inf"},
      {{"--agents", "30"}, "agents", "30"},
      {{"--tick-hz", "0"}, "tick_hz", "0"},
      {{"--duration", "-1"}, "duration_s", "-1"},
      {{"--kill", "L3@nan"}, "at_s", "nan"},
      {{"--resume", "L3@5"}, "action", "resume"},
      {{"--pause", "plant@5"}, "target", "plant"},
      {{"--fault", "L3:torque=-1@20"}, "faults[].value", "-1"},
      {{"--fault", "L3:melted@20"}, "faults[].mode", "melted"},
      {{"--fault", "central:open@20"}, "faults[].target", "central"},
      {{"--fault", "L3:stuck=99@20"}, "faults[].value", "99"},
      {{"--fault", "L3:open=2@20"}, "faults[].value", "2"},
      {{"--fault", "L3@20"}, "TARGET:MODE", "L3@20"},
      {{"--clear", "group-L@20"}, "faults[].target", "group-L"},
  };
  int i = 0;
  for (const auto& c : cases) {
    const std::string out = tmp.path() + "/run" + std::to_string(i++);
    auto r = run_cli(run_args(out, c.args), out, 30);
    EXPECT_EQ(r.exit_code, 2) << c.args[0] << " " << c.args[1] << ": " << r.output;
    EXPECT_NE(r.output.find(c.args[0]), std::string::npos) << r.output;  // the option is named
    EXPECT_NE(r.output.find(c.field), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.value), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << "a refused option must not start a run";
  }
}

TEST(Fleet, AContradictoryScheduleIsRefusedBeforeAnythingStartsNamingTheOption) {
  TempDir tmp;
  struct Case {
    std::vector<std::string> args;
    const char* option;  // the option named first
    const char* why;
  } cases[] = {
      {{"--kill", "L3@100"}, "--kill L3@100: faults[].at_s = 100", "after the end of the run (duration_s = 60 s)"},
      {{"--restart", "L3@20"}, "--restart L3@20: faults[].action = restart", "needs an earlier kill of L3"},
      {{"--kill", "L3@10", "--kill", "L3@12"}, "--kill L3@12: faults[].action = kill", "dead by then (killed at 10 s"},
      {{"--kill", "plant@10", "--restart", "plant@20"}, "--restart plant@20", "after the plant's kill at 10 s"},
      {{"--pause", "central@10", "--pause", "central@12"}, "--pause central@12", "paused by then"},
  };
  int i = 0;
  for (const auto& c : cases) {
    const std::string out = tmp.path() + "/run" + std::to_string(i++);
    std::vector<std::string> args = {"--duration", "60"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    auto r = run_cli(run_args(out, args), out, 30);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(c.option), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.why), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << "a refused schedule must not start a run";
  }
  // The same in a file names the file's entry.
  const std::string file = tmp.path() + "/restart.yaml";
  write_file(file,
             "name: restart\nduration_s: 10\ntrajectory:\n  segments:\n    - {type: straight, speed_mps: 1, "
             "duration_s: 10}\nfaults:\n  - {target: L1, action: restart, at_s: 5}\n");
  auto r = run_cli(run_args(tmp.path() + "/file-run", {file}), tmp.path() + "/file-run", 30);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("restart.yaml: faults[0].action = restart: a restart needs an earlier kill of L1"),
            std::string::npos)
      << r.output;
}

TEST(Fleet, FieldsPrintsTheScenarioReferenceAndRefusesAnUnknownPrefix) {
  TempDir tmp;
  auto r = run_cli({"fields", "control."}, tmp.path() + "/none", 30);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("control.t_on_s"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("robot.track_m"), std::string::npos) << r.output;
  r = run_cli({"fields", "--summary", "failures[]."}, tmp.path() + "/none", 30);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("failures[].detected_s"), std::string::npos) << r.output;
  r = run_cli({"fields", "colour"}, tmp.path() + "/none", 30);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no scenario field starts with 'colour'"), std::string::npos) << r.output;
}

TEST(Fleet, ABadFleetEnvironmentVariableIsRefusedBeforeAnythingStarts) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  for (const auto& [name, value] : {std::pair<const char*, const char*>{"MAPTR_DDS_LOG", "loud"},
                                    std::pair<const char*, const char*>{"MAPTR_AGENT_START", "vfork"}}) {
    setenv(name, value, 1);
    auto r = run_cli(run_args(out, {"--agents", "4", "--duration", "1"}), out, 30);
    unsetenv(name);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(std::string(name) + "=" + value + ": expected"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << "a refused run must not create its folder";
  }
}

TEST(Fleet, ADomainWhosePortsCannotHoldTheFleetIsRefused) {
  // RTPS ports: 7400 + 250 domain + 11 + 2 id. 256 agents are 262 participants: on domain 232
  // the last one's port would be 65933; domain 230 is the highest that fits.
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  auto r = run_cli({"run", "--agents", "256", "--domain", "232", "--duration", "1", "--out", out, "--quiet"}, out, 30);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--domain 232"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("65933"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("from 0 to 230"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out)) << "a refused run must not create its folder";
  // Out of the DDS range altogether: a usage error.
  auto r2 = run_cli({"run", "--domain", "240", "--out", out, "--quiet"}, out, 30);
  EXPECT_EQ(r2.exit_code, 2) << r2.output;
  EXPECT_NE(r2.output.find("240"), std::string::npos) << r2.output;
}

// A fleet that never gets ready (an external agent nobody starts) is run once more, on another
// domain with a fresh discovery server, before it is called aborted; the summary says so and
// the first attempt's files are kept.
TEST(Fleet, ADiscoveryTimeoutIsRetriedOnceAndTheSummarySaysSo) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(run_args(out, {"--agents", "4", "--duration", "2", "--external", "L0"}), out, 300);
  ASSERT_FALSE(r.timed_out) << r.output;
  EXPECT_NE(r.exit_code, 0);
  const std::string status = r.summary["status"];
  EXPECT_EQ(status.rfind("aborted: discovery timed out", 0), 0u) << status;
  ASSERT_TRUE(r.summary.contains("discovery_retry")) << r.summary.dump(2);
  const auto& retry = r.summary["discovery_retry"];
  EXPECT_EQ(retry["first_status"].get<std::string>().rfind("aborted: discovery timed out", 0), 0u);
  EXPECT_NE(retry["domain"].get<int>(), retry["first_domain"].get<int>());
  EXPECT_TRUE(std::ifstream(out + "/first-attempt/summary.json").good());
  // Each attempt's process logs in its own folder; the launcher's log holds both attempts, and
  // the first attempt's folder a copy of its part.
  EXPECT_TRUE(std::ifstream(out + "/first-attempt/logs/plant.log").good());
  EXPECT_TRUE(std::ifstream(out + "/logs/plant.log").good());
  const auto launches = [](const std::string& path) {
    std::ifstream f(path);
    int n = 0;
    for (std::string line; std::getline(f, line);)
      if (line.find("] launching ") != std::string::npos) ++n;
    return n;
  };
  EXPECT_EQ(launches(out + "/first-attempt/logs/launcher.log"), 1);
  EXPECT_EQ(launches(out + "/logs/launcher.log"), 2) << "the retry's lines go to RUN/logs/launcher.log";
  // The plant's log names what it never matched: the agent that was never started.
  std::ifstream plant_log(out + "/first-attempt/logs/plant.log");
  const std::string plant((std::istreambuf_iterator<char>(plant_log)), std::istreambuf_iterator<char>());
  EXPECT_NE(plant.find("discovery: no progress for"), std::string::npos) << plant;
  EXPECT_NE(plant.find("agent replies 3/4 (not matched: L0)"), std::string::npos) << plant;
}
