// `maptr top` against real fleets (ctest label `integration`): the plain-text snapshot of a
// 16-agent fleet that lost L3, and the full-screen view in a real terminal (tmux, 80x24): the
// agents, L3 dead, the final status once the run has ended, and `q` quits. Runs are paced to
// the wall clock and every check waits for what it expects with a generous timeout.
#include <gtest/gtest.h>
#include <signal.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <regex>

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

}  // namespace

TEST(Top, OnceShowsTheKilledAgentDeadAndFifteenLive) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  // Long enough that the snapshot is taken while the fleet runs; stopped once it is taken.
  const pid_t launcher = start_cli(run_args(out, {"--duration", "300", "--realtime", "--kill", "L3@5"}),
                                   tmp.path() + "/out.log");
  ASSERT_TRUE(wait_for([&] { return !read_json(out + "/fleet.json").is_null(); }, 60));
  std::string screen;
  const bool seen = wait_for([&] { return shows_l3_dead(screen = top_once(out)); }, 200);
  kill(launcher, SIGINT);
  EXPECT_GE(wait_child(launcher, 120), 0);
  ASSERT_TRUE(seen) << screen;
  // A finished run is watched through a replay of its recording, which this build does not make.
  const std::string after =
      shell(std::string(MAPTR_BIN_DIR) + "/maptr top --once --run " + out + " 2>&1; echo exit=$?");
  EXPECT_NE(after.find("no recording support"), std::string::npos) << after;
  EXPECT_NE(after.find("exit=2"), std::string::npos) << after;
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
  const std::string r = shell("cd " + tmp.path() + " && " + std::string(MAPTR_BIN_DIR) +
                              "/maptr top --once 2>&1; echo exit=$?");
  EXPECT_NE(r.find("no running fleet found"), std::string::npos) << r;
  EXPECT_NE(r.find("exit=2"), std::string::npos) << r;
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
