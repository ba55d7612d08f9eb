// A fault schedule that contradicts itself is refused before anything starts: a restart of a
// live process, a second kill of a dead one, a resume without a pause, a restart of the plant or
// anything after its kill; schedules that hold together are accepted.
#include <gtest/gtest.h>

#include "config/scenario.hpp"

namespace {

using maptr::config::FaultSpec;
using maptr::config::schedule_problem;

std::vector<FaultSpec> schedule(std::initializer_list<std::tuple<const char*, const char*, double>> faults) {
  std::vector<FaultSpec> out;
  for (const auto& [target, action, at] : faults) out.push_back(FaultSpec::of(target, action, at));
  return out;
}

void expect_problem(const std::vector<FaultSpec>& f, std::size_t index, const std::string& field, const std::string& words) {
  const auto p = schedule_problem(f);
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->index, index);
  EXPECT_EQ(p->field, field);
  EXPECT_NE(p->why.find(words), std::string::npos) << p->why;
}

TEST(Schedule, ARestartOfALiveProcessIsRefused) {
  expect_problem(schedule({{"L3", "restart", 20}}), 0, "action", "needs an earlier kill of L3");
  // Restarted, then restarted again without a kill between.
  expect_problem(schedule({{"L3", "kill", 5}, {"L3", "restart", 8}, {"L3", "restart", 9}}), 2, "action", "running");
}

TEST(Schedule, ASecondKillOfADeadProcessIsRefusedNamingTheFirst) {
  expect_problem(schedule({{"L3", "kill", 12}, {"L3", "kill", 10}}), 0, "action", "killed at 10 s");
}

TEST(Schedule, AResumeNeedsAPauseAndAPauseNeedsARunningProcess) {
  expect_problem(schedule({{"central", "resume", 5}}), 0, "action", "needs an earlier pause");
  expect_problem(schedule({{"central", "pause", 5}, {"central", "pause", 6}}), 1, "action", "paused at 5 s");
  expect_problem(schedule({{"central", "kill", 5}, {"central", "pause", 6}}), 1, "action", "dead");
  // A kill ends a pause: a resume after it has nothing to resume.
  expect_problem(schedule({{"central", "pause", 5}, {"central", "kill", 6}, {"central", "resume", 7}}), 2, "action",
                 "needs an earlier pause");
  expect_problem(schedule({{"central", "pause", 5}, {"central", "restart", 6}}), 1, "action", "resume it");
}

TEST(Schedule, ThePlantIsNeverRestartedAndNothingFollowsItsKill) {
  expect_problem(schedule({{"plant", "kill", 10}, {"plant", "restart", 20}}), 1, "at_s", "after the plant's kill at 10 s");
  expect_problem(schedule({{"plant", "restart", 20}}), 0, "target", "cannot be restarted");
  expect_problem(schedule({{"plant", "kill", 10}, {"L3", "kill", 12}}), 1, "at_s", "the run has ended");
  EXPECT_FALSE(schedule_problem(schedule({{"L3", "kill", 3}, {"plant", "kill", 5}})));
}

TEST(Schedule, HostLinksAreCutOnceAndHealedOnce) {
  expect_problem(schedule({{"h2", "heal", 5}}), 0, "action", "needs an earlier partition");
  expect_problem(schedule({{"h2", "partition", 5}, {"h2", "partition", 6}}), 1, "action", "cut by then");
  EXPECT_FALSE(schedule_problem(schedule({{"h2", "kill-host", 5}, {"h2", "heal", 9}})));
}

TEST(Schedule, SchedulesThatHoldTogetherAreAccepted) {
  // In list order the restart comes first: the schedule is taken in time order.
  EXPECT_FALSE(schedule_problem(schedule({{"L3", "restart", 8}, {"L3", "kill", 5}, {"L3", "kill", 12}})));
  EXPECT_FALSE(schedule_problem(schedule({{"L3", "kill", 5}, {"L3", "restart", 5}})));  // same time: list order
  EXPECT_FALSE(schedule_problem(schedule({{"group-L", "pause", 5}, {"group-L", "resume", 8}, {"group-L", "kill", 9}})));
  // The launcher restarts the discovery server itself: two kills are two outages.
  EXPECT_FALSE(schedule_problem(schedule({{"discovery", "kill", 3}, {"discovery", "kill", 9}})));
  expect_problem(schedule({{"discovery", "restart", 3}}), 0, "action", "restarts the discovery server by itself");
  // A kill-host leaves the processes' states to the placement: a restart after it is accepted.
  EXPECT_FALSE(schedule_problem(schedule({{"h2", "kill-host", 10}, {"L2", "restart", 15}})));
  // The agents' own faults are not followed: a clear without a fault does nothing.
  EXPECT_FALSE(schedule_problem(schedule({{"L3", "clear", 5}, {"L3", "fault", 6}, {"L3", "fault", 7}})));
  EXPECT_FALSE(schedule_problem({}));
}

}  // namespace
