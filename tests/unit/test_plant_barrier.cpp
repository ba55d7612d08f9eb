// Plant lock-step barrier (plant/barrier.hpp): who must answer tick k, completeness, the late
// members, the deadline and the resends to restarted members (explicit wall times).
#include <gtest/gtest.h>

#include <algorithm>

#include "plant/barrier.hpp"

namespace {

using namespace maptr::plant;

constexpr int kPerSide = 2;
const MemberId kL1{Role::kAgent, 0, 1};
const MemberId kR0{Role::kAgent, 1, 0};

WriterId writer(uint8_t n) {
  WriterId w;
  w.bytes[0] = n;
  w.set = true;
  return w;
}

Membership fresh() {
  return Membership(kPerSide, [] { return 0.0; });
}

void answer_all_but(Membership& m, const std::vector<MemberId>& silent) {
  for (const auto& id : m.all())
    if (std::find(silent.begin(), silent.end(), id) == silent.end()) m.on_answer(id, writer(1));
}

std::vector<std::string> names(const std::vector<MemberId>& ids) {
  std::vector<std::string> out;
  for (const auto& id : ids) out.push_back(member_name(id));
  return out;
}

TEST(PlantBarrier, CompleteWhenEveryLiveMemberAnswered) {
  Membership m = fresh();
  m.begin_tick();
  EXPECT_EQ(names(Barrier::expected(m)),
            (std::vector<std::string>{"L0", "L1", "R0", "R1", "group-L", "group-R", "central"}));
  EXPECT_FALSE(Barrier::complete(m));
  answer_all_but(m, {});
  EXPECT_TRUE(Barrier::complete(m));
  EXPECT_TRUE(Barrier::late(m).empty());
  m.begin_tick();  // the next tick: nobody has answered it
  EXPECT_FALSE(Barrier::complete(m));
  EXPECT_EQ(Barrier::late(m).size(), 7u);
}

TEST(PlantBarrier, DeadMemberIsNotWaitedFor) {
  Membership m = fresh();
  m.on_launcher(1, LauncherEvent::kDied, "L1");
  m.begin_tick();
  answer_all_but(m, {kL1});
  EXPECT_TRUE(Barrier::complete(m));
  EXPECT_EQ(names(Barrier::expected(m)),
            (std::vector<std::string>{"L0", "R0", "R1", "group-L", "group-R", "central"}));
}

TEST(PlantBarrier, LateMemberIsNamedAndDeclaredDeadAfterTheDeadline) {
  Membership m = fresh();
  Barrier b(5.1, 0.2);
  m.begin_tick();
  b.start(100.0);
  answer_all_but(m, {kR0});
  EXPECT_FALSE(Barrier::complete(m));
  EXPECT_EQ(names(Barrier::late(m)), std::vector<std::string>{"R0"});
  EXPECT_FALSE(b.deadline_passed(105.0));
  EXPECT_TRUE(b.deadline_passed(105.2));
  EXPECT_EQ(m.on_deadline(), 1);
  EXPECT_TRUE(Barrier::complete(m));
  EXPECT_TRUE(Barrier::late(m).empty());
}

TEST(PlantBarrier, RestartedMemberIsExpectedAndTheTickResent) {
  Membership m = fresh();
  Barrier b(5.0, 0.2);
  m.on_launcher(1, LauncherEvent::kDied, "L1");
  m.begin_tick();
  b.start(10.0);
  answer_all_but(m, {kL1});
  EXPECT_TRUE(Barrier::complete(m));
  EXPECT_FALSE(b.resend_due(m, 11.0));              // nobody rejoining
  m.on_launcher(2, LauncherEvent::kStarted, "L1");  // MEMBER_STARTED: expected from now on
  EXPECT_FALSE(Barrier::complete(m));
  EXPECT_EQ(names(Barrier::late(m)), std::vector<std::string>{"L1"});
  EXPECT_TRUE(b.resend_due(m, 11.0));
  EXPECT_FALSE(b.resend_due(m, 11.1));  // within the resend interval of the last send
  EXPECT_TRUE(b.resend_due(m, 11.3));
  m.on_answer(kL1, writer(2));
  EXPECT_TRUE(Barrier::complete(m));
  EXPECT_FALSE(b.resend_due(m, 20.0));
}

}  // namespace

namespace {

// An idle agent not due (excused) is not waited for; a rejoining one always is.
TEST(PlantBarrier, ExcusedIdleAgentsAreNotWaitedForButRejoiningOnesAre) {
  Membership m = fresh();
  m.begin_tick([](int side, int index) { return side == 0 && index == 1; });  // L1 idle, not due
  answer_all_but(m, {kL1});
  EXPECT_TRUE(Barrier::complete(m));
  EXPECT_EQ(Barrier::late_count(m), 0);

  m.on_launcher(1, LauncherEvent::kStarted, "L1");  // restarted: rejoining
  m.begin_tick([](int side, int index) { return side == 0 && index == 1; });
  answer_all_but(m, {kL1});
  EXPECT_FALSE(Barrier::complete(m));
  EXPECT_EQ(Barrier::late_count(m), 1);
  EXPECT_EQ(names(Barrier::late(m)), std::vector<std::string>{"L1"});
}

// A tick is sent again only when no answer came for the repair interval, which follows the
// typical barrier time and never goes below its floor.
TEST(PlantBarrier, RepairWhenNoAnswerCameForTheRepairInterval) {
  Barrier b(10.0, 0.2);
  b.set_repair(0.001, 10.0, 0.05);  // 10 x 1 ms is below the 50 ms floor
  b.start(100.0);
  EXPECT_FALSE(b.repair_due(3, 100.04));  // answers arrived: progress
  EXPECT_FALSE(b.repair_due(3, 100.08));  // 40 ms without: not yet
  EXPECT_TRUE(b.repair_due(3, 100.095));  // 55 ms without: send again
  EXPECT_FALSE(b.repair_due(3, 100.12));  // the send restarts the interval
  b.set_repair(0.02, 10.0, 0.05);         // typical 20 ms: 200 ms
  EXPECT_FALSE(b.repair_due(3, 100.25));
  EXPECT_TRUE(b.repair_due(3, 100.35));
}

}  // namespace
