// How the launcher starts a child (deploy/fleet/children.hpp: spawn): without copying the
// launcher, yet with what a forked child had: its own process group, no signal blocked, the
// fleet's environment and its output in RUN_DIR/logs/NAME.stderr.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "deploy/fleet/children.hpp"

namespace {

namespace fs = std::filesystem;
using maptr::deploy::fleet::Child;
using maptr::deploy::fleet::spawn;

struct RunDir {
  fs::path path;
  RunDir() : path(fs::temp_directory_path() / ("maptr-spawn-" + std::to_string(getpid()))) {
    fs::create_directories(path / "logs");
  }
  ~RunDir() { fs::remove_all(path); }
  std::string log(const std::string& name) const {
    std::ifstream f(path / "logs" / (name + ".stderr"));
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
  }
};

Child shell(const std::string& name, const std::string& script) {
  Child c;
  c.name = name;
  c.binary = "/bin/sh";
  c.args = {"-c", script};
  return c;
}

Child program(const std::string& name, const std::string& binary, std::vector<std::string> args) {
  Child c;
  c.name = name;
  c.binary = binary;
  c.args = std::move(args);
  return c;
}

int wait_exit(pid_t pid) {
  int st = 0;
  EXPECT_EQ(waitpid(pid, &st, 0), pid);
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

void on_usr1(int) {}

TEST(Spawn, AChildHasItsOwnGroupNoBlockedSignalAndTheFleetsEnvironment) {
  RunDir dir;
  // The launcher blocks signals around the start and handles some: neither reaches the child.
  struct sigaction sa {};
  sa.sa_handler = on_usr1;
  struct sigaction old {};
  sigaction(SIGUSR1, &sa, &old);
  sigset_t usr2, before, after;
  sigemptyset(&usr2);
  sigaddset(&usr2, SIGUSR2);
  pthread_sigmask(SIG_BLOCK, &usr2, &before);

  // Three children, each a program that changes neither its signals nor its group: its status,
  // its stat line (pid and process group) and its environment go to its log.
  Child status = program("status", "/bin/cat", {"/proc/self/status"});
  Child stat = program("stat", "/bin/cat", {"/proc/self/stat"});
  Child env = program("env", "/usr/bin/env", {});
  for (Child* c : {&status, &stat, &env}) {
    spawn(*c, dir.path.string(), {{"MAPTR_PROBE", "yes"}}, 42);
    ASSERT_GT(c->pid, 0);
    EXPECT_TRUE(c->running);
    EXPECT_EQ(c->starts, 1);
    EXPECT_EQ(wait_exit(c->pid), 0);
  }

  pthread_sigmask(SIG_SETMASK, nullptr, &after);
  pthread_sigmask(SIG_SETMASK, &before, nullptr);
  sigaction(SIGUSR1, &old, nullptr);
  EXPECT_TRUE(sigismember(&after, SIGUSR2)) << "the launcher's own mask is given back unchanged";
  EXPECT_FALSE(sigismember(&after, SIGUSR1));

  // The child's blocked set is the launcher thread's (SIGUSR2 here, bit 11), not "all" from the
  // start; no handler of the launcher is left in it.
  const std::string st = dir.log("status");
  EXPECT_NE(st.find("SigBlk:\t0000000000000800"), std::string::npos) << st;
  EXPECT_NE(st.find("SigCgt:\t0000000000000000"), std::string::npos) << st;
  // Its own process group: the stat line's first field (pid) and fifth (pgrp) are both its pid.
  std::istringstream line(dir.log("stat"));
  std::string pid, comm, state, ppid, pgrp;
  line >> pid >> comm >> state >> ppid >> pgrp;
  EXPECT_EQ(pid, std::to_string(stat.pid));
  EXPECT_EQ(pgrp, std::to_string(stat.pid));
  EXPECT_EQ(ppid, std::to_string(getpid()));
  const std::string e = "\n" + dir.log("env");
  EXPECT_NE(e.find("\nMAPTR_PARTICIPANT_ID=42\n"), std::string::npos) << e;
  EXPECT_NE(e.find("\nMAPTR_PROBE=yes\n"), std::string::npos) << e;
}

TEST(Spawn, ABinaryThatCannotStartExits127) {
  RunDir dir;
  Child c;
  c.name = "missing";
  c.binary = (dir.path / "no-such-binary").string();
  spawn(c, dir.path.string(), {}, 0);
  ASSERT_GT(c.pid, 0);
  EXPECT_EQ(wait_exit(c.pid), 127);
}

TEST(Spawn, ManyChildrenInARowEachStartOnce) {
  // The start stack is re-used: every child must have left it (exec or exit) before the next.
  RunDir dir;
  for (int i = 0; i < 50; ++i) {
    Child c = shell("c" + std::to_string(i), "echo $MAPTR_PARTICIPANT_ID");
    spawn(c, dir.path.string(), {}, i);
    ASSERT_EQ(wait_exit(c.pid), 0);
    EXPECT_EQ(dir.log(c.name), std::to_string(i) + "\n");
  }
}

}  // namespace
