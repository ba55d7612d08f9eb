// Whom the launcher believes when a process says it is ready (deploy/fleet/ready_check.hpp).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <iterator>
#include <fstream>
#include <string>

#include "deploy/fleet/ready_check.hpp"

namespace {

using maptr::deploy::fleet::external_pid_problem;
using maptr::deploy::fleet::judge_ready;
using maptr::deploy::fleet::ReadyClaim;
using maptr::deploy::fleet::ReadyVerdict;

ReadyClaim own_child() {
  ReadyClaim c;
  c.known_name = true;
  c.from_current_participant = true;
  c.pid_matches = true;
  return c;
}

TEST(FleetReady, TheExpectedParticipantWithTheStartedPidIsBelieved) {
  EXPECT_EQ(judge_ready(own_child()), ReadyVerdict::kTaken);
}

TEST(FleetReady, AnUnknownNameIsForged) {
  ReadyClaim c = own_child();
  c.known_name = false;
  EXPECT_EQ(judge_ready(c), ReadyVerdict::kForged);
}

TEST(FleetReady, AnotherParticipantIsForgedEvenWithTheRightPid) {
  ReadyClaim c = own_child();
  c.from_current_participant = false;
  EXPECT_EQ(judge_ready(c), ReadyVerdict::kForged);
}

TEST(FleetReady, TheRightParticipantWithAnotherPidIsForged) {
  // A forger that copied the prefix but points at another process.
  ReadyClaim c = own_child();
  c.pid_matches = false;
  EXPECT_EQ(judge_ready(c), ReadyVerdict::kForged);
}

TEST(FleetReady, AnEarlierStartIsStaleNotReady) {
  ReadyClaim c = own_child();
  c.from_current_participant = false;
  c.from_earlier_participant = true;
  EXPECT_EQ(judge_ready(c), ReadyVerdict::kStale);
}

TEST(FleetReady, AnExternalProcessNeedsItsPidChecked) {
  ReadyClaim c = own_child();
  c.external = true;
  c.pid_matches = false;
  EXPECT_EQ(judge_ready(c), ReadyVerdict::kForged);
  c.external_pid_ok = true;
  EXPECT_EQ(judge_ready(c), ReadyVerdict::kTaken);
  c.from_current_participant = false;
  EXPECT_EQ(judge_ready(c), ReadyVerdict::kForged);
}

/// A child running /bin/sleep with the given environment; killed and reaped on destruction.
struct Sleeper {
  pid_t pid = -1;
  explicit Sleeper(const char* fleet_env, const char* part_env) {
    pid = fork();
    if (pid == 0) {
      char* const argv[] = {const_cast<char*>("sleep"), const_cast<char*>("30"), nullptr};
      char* const envp[] = {const_cast<char*>(fleet_env), const_cast<char*>(part_env), nullptr};
      execve("/bin/sleep", argv, envp);
      _exit(127);
    }
    // Until its exec is done, /proc shows the test's own executable, and for a moment after the
    // new executable an empty environment: wait for both, however long a loaded machine takes
    // (at most 60 s).
    const auto want = std::filesystem::canonical("/bin/sleep");
    for (int i = 0; i < 6000; ++i) {
      std::error_code ec;
      std::ifstream env("/proc/" + std::to_string(pid) + "/environ", std::ios::binary);
      const std::string text((std::istreambuf_iterator<char>(env)), std::istreambuf_iterator<char>());
      if (std::filesystem::read_symlink("/proc/" + std::to_string(pid) + "/exe", ec) == want &&
          text.find(fleet_env) != std::string::npos)
        break;
      usleep(10000);
    }
  }
  ~Sleeper() {
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
  }
};

TEST(FleetReady, AnExternalPidMustRunTheBinaryWithTheFleetsEnvironment) {
  Sleeper s("MAPTR_FLEET_ID=77", "MAPTR_PARTICIPANT_ID=9");
  bool unreadable = true;
  EXPECT_EQ(external_pid_problem(s.pid, "/bin/sleep", 77, 9, unreadable), std::nullopt);
  EXPECT_FALSE(unreadable);
  // Another fleet, another participant, another binary: each named.
  auto problem = external_pid_problem(s.pid, "/bin/sleep", 78, 9, unreadable);
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("MAPTR_FLEET_ID=78"), std::string::npos) << *problem;
  problem = external_pid_problem(s.pid, "/bin/sleep", 77, 10, unreadable);
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("MAPTR_PARTICIPANT_ID=10"), std::string::npos) << *problem;
  problem = external_pid_problem(s.pid, "/bin/true", 77, 9, unreadable);
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("not /bin/true"), std::string::npos) << *problem;
}

TEST(FleetReady, PidsThatAreNoProcessOfTheFleetAreRefused) {
  bool unreadable = true;
  // 0, -1 and 1 would signal the launcher's group, every process, or init.
  for (pid_t pid : {0, -1, 1}) {
    EXPECT_TRUE(external_pid_problem(pid, "/bin/sleep", 1, 1, unreadable)) << pid;
    EXPECT_FALSE(unreadable);
  }
  // The test's own pid runs another binary.
  EXPECT_TRUE(external_pid_problem(getpid(), "/bin/sleep", 1, 1, unreadable));
}

}  // namespace

TEST(FleetReady, TheMembersThePlantMissesStartAgainRatherThanThePlant) {
  using maptr::deploy::fleet::rematch_choice;
  using V = std::vector<std::string>;
  const std::set<std::string> ready{"L0", "L1", "R0", "R1", "group-L", "group-R", "central"};
  // Only the plant is not ready and it names ready members: those start again, each once.
  EXPECT_EQ(rematch_choice({"plant"}, {"R1", "L0", "R1"}, ready), (V{"R1", "L0"}));
  // Without a report, or naming a process that is not a ready member: the plant itself.
  EXPECT_EQ(rematch_choice({"plant"}, {}, ready), V{"plant"});
  EXPECT_EQ(rematch_choice({"plant"}, {"R1", "launcher"}, ready), V{"plant"});
  // Others not ready too: those, never the plant, whatever it reports.
  EXPECT_EQ(rematch_choice({"plant", "L1", "R0"}, {"R1"}, ready), (V{"L1", "R0"}));
  EXPECT_EQ(rematch_choice({"L1"}, {"R1"}, ready), V{"L1"});
  EXPECT_TRUE(rematch_choice({}, {"R1"}, ready).empty());
}
