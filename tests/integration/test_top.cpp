// `maptr top` against real fleets (ctest label `integration`): the plain-text snapshot of a
// 16-agent fleet that lost L3, and the full-screen view in a real terminal (tmux, 80x24): the
// agents, L3 dead, the final status once the run has ended, and `q` quits; a finished run
// watched through a replay of its recording, and one without a recording. Runs are paced to
// the wall clock and every check waits for what it expects with a generous timeout; the
// snapshot of a replay is taken once the replay has ended, so it races nothing.
#include <gtest/gtest.h>
#include <signal.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <regex>
#include <sstream>

#include "tests/integration/fleet_runner.hpp"

using namespace maptr::testing;

namespace {

/// Standard output of a shell command.
std::string shell(const std::string& cmd) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof(buf), p)) > 0;) out.append(buf, n);
  pclose(p);
  return out;
}

std::string top_once(const std::string& run_dir) {
  return shell(std::string(MAPTR_BIN_DIR) + "/maptr top --once --timeout 60 --run " + run_dir + " 2>&1");
}

bool shows_l3_dead(const std::string& screen) {
  return screen.find("L3   dead") != std::string::npos && screen.find("live 15/16") != std::string::npos;
}

/// Agent cells of a detailed snapshot ("L3   dead ...") with state `state`.
int cells_with(const std::string& screen, const std::string& state) {
  const std::regex cell("\\b[LR][0-9]+ +" + state + " ");
  return static_cast<int>(
      std::distance(std::sregex_iterator(screen.begin(), screen.end(), cell), std::sregex_iterator()));
}

/// The status line the view prints for a summary (the same rounding as the screen).
std::string final_status_line(const nlohmann::json& s) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), "final status: %s (%s) at t %.2f s, energy %.1f J, %.1f m",
                s.value("status", "?").c_str(), s.at("plant").value("end_reason", "?").c_str(),
                s.value("sim_time_s", NAN), s.value("energy_J", NAN), s.value("distance_m", NAN));
  return buf;
}

/// A side's row of the side table: battery V, discharge mAh, active agents.
struct SideRow {
  double battery_V = NAN, discharge_mAh = NAN;
  int active = -1;
};
SideRow side_row(const std::string& screen, const std::string& side) {
  const std::regex row("\\n" + side + " +([0-9.]+) V +([0-9.]+) mAh +([0-9]+)/");
  std::smatch m;
  if (!std::regex_search(screen, m, row)) return {};
  return {std::stod(m[1]), std::stod(m[2]), std::stoi(m[3])};
}

}  // namespace

TEST(Top, OnceShowsTheKilledAgentDeadAndFifteenLive) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  // Long enough that the snapshot is taken while the fleet runs; stopped once it is taken.
  const pid_t launcher = start_cli(run_args(out, {"--duration", "300", "--realtime", "--kill", "L3@5"}),
                                   tmp.path() + "/out.log");
  ASSERT_TRUE(wait_for([&] { return !read_json(out + "/fleet.json").is_null(); }, 60));
  std::string screen;
  // The dead cell comes with the plant's ticks, the event line with the launcher's membership
  // event: two writers, so a snapshot may show one before the other. Wait for both.
  const bool seen = wait_for(
      [&] {
        screen = top_once(out);
        return shows_l3_dead(screen) && screen.find("L3 died") != std::string::npos;
      },
      200);
  kill(launcher, SIGINT);
  EXPECT_GE(wait_child(launcher, 120), 0);
  ASSERT_TRUE(seen) << screen;
  std::cout << screen;
  EXPECT_EQ(cells_with(screen, "dead"), 1) << screen;
  EXPECT_NE(screen.find("L3 died"), std::string::npos) << screen;
  // Every other agent has a live state.
  int live_cells = 0;
  for (const char* st : {"active", "idle", "holding", "coasting", "stopping"})
    live_cells += cells_with(screen, st);
  EXPECT_EQ(live_cells, 15) << screen;
}

TEST(Top, NoFleetIsAClearError) {
  TempDir tmp;
  // A registry of its own: a fleet the machine's user runs meanwhile is not this test's.
  const std::string r = shell("cd " + tmp.path() + " && XDG_RUNTIME_DIR=" + tmp.path() + " " +
                              std::string(MAPTR_BIN_DIR) + "/maptr top --once 2>&1; echo exit=$?");
  EXPECT_NE(r.find("no running fleet (none registered, none under runs/"), std::string::npos) << r;
  EXPECT_NE(r.find("exit=2"), std::string::npos) << r;
}

// A fleet whose --out is outside runs/ registers itself: `maptr ps` lists it, `top` and `kill`
// find it without --run, and its entry is gone when it ends.
TEST(Top, AFleetOutsideRunsIsFoundByPsTopAndKill) {
  TempDir tmp;
  const std::string xdg = tmp.path() + "/xdg", out = tmp.path() + "/elsewhere/run";
  std::filesystem::create_directories(xdg);
  setenv("XDG_RUNTIME_DIR", xdg.c_str(), 1);
  const pid_t launcher = start_cli(run_args(out, {"--duration", "300", "--realtime"}), tmp.path() + "/out.log");
  unsetenv("XDG_RUNTIME_DIR");
  const std::string env = "cd " + tmp.path() + " && XDG_RUNTIME_DIR=" + xdg + " " + MAPTR_BIN_DIR + "/maptr ";
  std::string ps;
  const bool listed = wait_for(
      [&] {
        ps = shell(env + "ps 2>&1");
        return ps.find(out) != std::string::npos && ps.find("paper") != std::string::npos;
      },
      120);
  std::string screen, sent;
  if (listed) {
    wait_for([&] { return !read_json(out + "/fleet.json").is_null(); }, 60);
    screen = shell(env + "top --once --timeout 60 2>&1; echo exit=$?");
    sent = shell(env + "kill L3 2>&1; echo exit=$?");
  }
  // The launcher records the command's kill before it ends.
  const bool killed = listed && wait_for([&] { return top_once(out).find("L3 died") != std::string::npos; }, 120);
  kill(launcher, SIGINT);
  EXPECT_GE(wait_child(launcher, 120), 0);
  ASSERT_TRUE(listed) << ps;
  EXPECT_NE(screen.find("exit=0"), std::string::npos) << screen;
  EXPECT_NE(screen.find("L0"), std::string::npos) << screen;
  EXPECT_NE(sent.find("sent 'kill L3' to the fleet in " + out), std::string::npos) << sent;
  EXPECT_TRUE(killed);
  // Ended: unregistered.
  EXPECT_NE(shell(env + "ps 2>&1").find("no running fleet"), std::string::npos);
  int entries = 0;
  for (const auto& e : std::filesystem::directory_iterator(xdg + "/maptr/fleets")) entries += e.path().extension() == ".json";
  EXPECT_EQ(entries, 0);
}

TEST(Top, FullScreenUnderTmuxShowsAgentsTheDeadOneAndTheFinalStatus) {
  if (shell("command -v tmux").empty())
    GTEST_SKIP() << "tmux is not installed: the full-screen test is skipped";
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  const std::string session = "maptr-top-test-" + std::to_string(getpid());
  const std::string tmux = "tmux -L " + session;  // a private server: the user's sessions are untouched
  const pid_t launcher =
      start_cli(run_args(out, {"--duration", "20", "--realtime", "--kill", "L3@5"}), tmp.path() + "/out.log");
  ASSERT_TRUE(wait_for([&] { return !read_json(out + "/fleet.json").is_null(); }, 60));
  const std::string cmd =
      std::string(MAPTR_BIN_DIR) + "/maptr top --run " + out + "; echo top-exited=$?; sleep 60";
  shell(tmux + " new-session -d -s " + session + " -x 80 -y 24 '" + cmd + "'");
  auto capture = [&] { return shell(tmux + " capture-pane -p -t " + session); };
  std::string screen;
  const bool running_view = wait_for(
      [&] {
        screen = capture();
        return shows_l3_dead(screen) && screen.find("R7   active") != std::string::npos;
      },
      120);
  const int code = wait_child(launcher, 300);
  const std::string status = read_json(out + "/summary.json").value("status", "?");
  const bool final_view =
      wait_for([&] { return (screen = capture()).find("final status: " + status) != std::string::npos; }, 60);
  const std::string final_screen = screen;
  shell(tmux + " send-keys -t " + session + " q");
  const bool quit =
      wait_for([&] { return (screen = capture()).find("top-exited=0") != std::string::npos; }, 30);
  shell(tmux + " kill-server 2>/dev/null");
  EXPECT_TRUE(code == 0 || code == 3) << "exit " << code;  // ok or degraded
  EXPECT_TRUE(running_view) << screen;
  EXPECT_TRUE(final_view) << final_screen;
  std::cout << final_screen;
  EXPECT_NE(final_screen.find("L3   dead"), std::string::npos) << final_screen;
  EXPECT_TRUE(quit) << screen;
}

TEST(Top, OnceOnAFinishedRunReplaysItsRecordingAndShowsTheRecordedEnd) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  const CliResult run = run_cli(run_args(out, {"--duration", "10", "--kill", "L3@5"}), out, 300);
  ASSERT_TRUE(run.exit_code == 0 || run.exit_code == 3) << run.output;  // ok or degraded
  ASSERT_TRUE(std::filesystem::exists(out + "/run.mcap")) << run.output;
  // The snapshot of a replay waits for the replay's end: no race with the run's pace.
  const CliResult top = run_cli({"top", "--once", "--run", out, "--rate", "2"}, tmp.path() + "/top", 300);
  const std::string& screen = top.output;
  std::cout << screen;
  ASSERT_EQ(top.exit_code, 0) << screen;
  EXPECT_NE(screen.find("replay 2x  finished"), std::string::npos) << screen;
  EXPECT_TRUE(shows_l3_dead(screen)) << screen;
  EXPECT_EQ(cells_with(screen, "dead"), 1) << screen;
  EXPECT_NE(screen.find("L3 died"), std::string::npos) << screen;
  int live_cells = 0;
  for (const char* st : {"active", "idle", "holding", "coasting", "stopping"})
    live_cells += cells_with(screen, st);
  EXPECT_EQ(live_cells, 15) << screen;
  // The recorded end, as summary.json has it: status, time, energy, distance, and per side the
  // battery, its discharge and the active agents (within the screen's rounding).
  const nlohmann::json& s = run.summary;
  EXPECT_NE(screen.find(final_status_line(s)), std::string::npos) << final_status_line(s) << "\n" << screen;
  for (const char* side : {"L", "R"}) {
    const SideRow r = side_row(screen, side);
    EXPECT_NEAR(r.battery_V, s.at("plant").at("battery_V").value(side, NAN), 0.005 + 1e-9) << side;
    EXPECT_NEAR(r.discharge_mAh, s.at("battery_discharge_mAh").value(side, NAN), 0.0005 + 1e-9) << side;
    EXPECT_EQ(r.active, s.at("active_agents").value(side, -1)) << side;
  }
}

/// The event lines of a `top --once` screen ("t    12.00 s    L3 died (scheduled)"), in order.
std::vector<std::string> event_lines(const std::string& screen) {
  std::vector<std::string> out;
  std::istringstream in(screen);
  bool in_events = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("events:", 0) == 0) {
      in_events = true;
      continue;
    }
    if (in_events && line.rfind("  t ", 0) == 0)
      out.push_back(line);
    else if (in_events)
      break;
  }
  return out;
}

// A replay shows the run's own events: every membership event of summary.json, at its time, in
// order, between the faults named with their ticks; two replays give the same list.
TEST(Top, AReplayListsEveryEventOfTheRunInOrderTheSameEveryTime) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  const CliResult run =
      run_cli(run_args(out, {"--duration", "16", "--kill", "L3@4", "--kill", "L4@5", "--kill", "group-L@7", "--restart",
                             "group-L@9", "--pause", "central@11", "--resume", "central@12"}),
              out, 300);
  ASSERT_TRUE(run.exit_code == 0 || run.exit_code == 3) << run.output;  // ok or degraded
  std::vector<std::string> expected;
  for (const auto& e : run.summary.at("membership_events")) {
    char buf[160];
    std::snprintf(buf, sizeof(buf), "  t %8.2f s    %s %s (%s)", e.value("t_s", 0.0), e.value("process", "").c_str(),
                  e.value("kind", "").c_str(), e.value("cause", "").c_str());
    expected.push_back(buf);
  }
  ASSERT_GE(expected.size(), 6u) << run.summary.at("membership_events").dump(1);
  std::vector<std::string> first;
  for (int k = 0; k < 2; ++k) {
    const CliResult top = run_cli({"top", "--once", "--run", out, "--rate", "8"}, tmp.path() + "/top", 300);
    ASSERT_EQ(top.exit_code, 0) << top.output;
    const auto lines = event_lines(top.output);
    // The membership events, in the order and at the times the run recorded them.
    std::vector<std::string> members;
    for (const auto& l : lines)
      if (l.find("scheduled ") == std::string::npos && l.find("by its group") == std::string::npos &&
          l.find("run finished") == std::string::npos && l.find("run aborted") == std::string::npos)
        members.push_back(l);
    EXPECT_EQ(members, expected) << top.output;
    // Each fault named with its tick (100 Hz: at_s x 100).
    EXPECT_NE(top.output.find("scheduled kill of L3 (tick 400)"), std::string::npos) << top.output;
    EXPECT_NE(top.output.find("scheduled pause of central (tick 1100)"), std::string::npos) << top.output;
    EXPECT_EQ(top.output.find("central started"), std::string::npos) << "a pause is not a start\n" << top.output;
    if (k == 0)
      first = lines;
    else
      EXPECT_EQ(lines, first) << "two replays, two event lists";
  }
}

TEST(Top, AFinishedRunWithoutARecordingIsAClearError) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  const CliResult run = run_cli(run_args(out, {"--duration", "2", "--record", "none"}), out, 300);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  ASSERT_FALSE(std::filesystem::exists(out + "/run.mcap"));
  const CliResult top = run_cli({"top", "--once", "--run", out}, tmp.path() + "/top", 120);
  EXPECT_EQ(top.exit_code, 2) << top.output;
  EXPECT_NE(top.output.find("no recording to replay (no run.mcap"), std::string::npos) << top.output;
}
