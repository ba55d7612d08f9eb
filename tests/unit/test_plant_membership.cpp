// Plant membership (plant/membership.hpp): the three sources (launcher events, DDS
// liveliness, the barrier deadline), re-admission and the event log.
#include <gtest/gtest.h>

#include "plant/membership.hpp"

namespace {

using namespace maptr::plant;

constexpr int kPerSide = 4;

WriterId writer(uint8_t n) {
  WriterId w;
  w.bytes[15] = n;
  w.set = true;
  return w;
}

const MemberId kL1{Role::kAgent, 0, 1};
const MemberId kR2{Role::kAgent, 1, 2};
const MemberId kGroupL{Role::kGroup, 0, 0};
const MemberId kCentral{Role::kCentral, 0, 0};

/// A membership whose wall clock advances 1 ms per reading from 1000 ms.
struct PlantMembership : ::testing::Test {
  double wall = 1000.0;
  Membership m{kPerSide, [this] { return wall += 1.0; }};
};

TEST_F(PlantMembership, EveryMemberStartsLiveAndNamed) {
  EXPECT_EQ(m.all().size(), 2u * kPerSide + 3u);
  for (const auto& id : m.all()) EXPECT_TRUE(m.at(id).live) << member_name(id);
  EXPECT_EQ(member_name(kL1), "L1");
  EXPECT_EQ(member_name(kR2), "R2");
  EXPECT_EQ(member_name(kGroupL), "group-L");
  EXPECT_EQ(member_name(kCentral), "central");
  EXPECT_EQ(m.find("R2"), kR2);
  EXPECT_EQ(m.find("group-L"), kGroupL);
  EXPECT_FALSE(m.find("L4"));  // index beyond the side
  EXPECT_FALSE(m.find("plant"));
  EXPECT_EQ(m.live_count(0), kPerSide);
}

TEST_F(PlantMembership, LauncherDeathEndsTheWaitAndIsRecordedOnce) {
  m.set_time(5.0);
  m.on_launcher(3, LauncherEvent::kDied, "L1");
  m.on_launcher(4, LauncherEvent::kDied, "L1");  // a second report changes nothing
  EXPECT_FALSE(m.at(kL1).live);
  EXPECT_EQ(m.live_mask(0), (std::vector<uint8_t>{1, 0, 1, 1}));
  EXPECT_EQ(m.live_count(0), kPerSide - 1);
  EXPECT_EQ(m.launcher_seq(), 4u);
  ASSERT_EQ(m.records().size(), 1u);
  EXPECT_EQ(m.records()[0].name, "L1");
  EXPECT_EQ(m.records()[0].event, "died (launcher)");
  EXPECT_DOUBLE_EQ(m.records()[0].t_s, 5.0);
  EXPECT_DOUBLE_EQ(m.records()[0].wall_ms, 1001.0);
}

TEST_F(PlantMembership, LauncherEventAboutThePlantOnlyCountsItsNumber) {
  EXPECT_TRUE(m.on_launcher(7, LauncherEvent::kPaused, "plant"));
  EXPECT_EQ(m.launcher_seq(), 7u);
  EXPECT_TRUE(m.records().empty());
}

TEST_F(PlantMembership, AnUnknownKindOrAnOldNumberIsNotAppliedAndDoesNotMoveTheSequence) {
  ASSERT_TRUE(m.on_launcher(7, LauncherEvent::kStarted, "L2"));
  // An unknown kind says nothing: a later gate must still wait for event 8.
  EXPECT_FALSE(m.on_launcher(8, LauncherEvent::kOther, "L1"));
  EXPECT_EQ(m.launcher_seq(), 7u);
  // Not above the last applied: a copy or a forgery, not news.
  EXPECT_FALSE(m.on_launcher(7, LauncherEvent::kDied, "L1"));
  EXPECT_FALSE(m.on_launcher(3, LauncherEvent::kDied, "L1"));
  EXPECT_TRUE(m.at(kL1).live);
  EXPECT_EQ(m.launcher_seq(), 7u);
  EXPECT_TRUE(m.on_launcher(8, LauncherEvent::kDied, "L1"));
  EXPECT_FALSE(m.at(kL1).live);
}

TEST_F(PlantMembership, LivelinessLossOfTheCurrentWriterKills) {
  m.on_answer(kL1, writer(1));
  m.on_answer(kCentral, writer(9));
  m.set_time(2.5);
  m.on_liveliness_lost(Role::kGroup, writer(1));  // another topic's writer: not L1's
  EXPECT_TRUE(m.at(kL1).live);
  m.on_liveliness_lost(Role::kAgent, writer(1));
  EXPECT_FALSE(m.at(kL1).live);
  EXPECT_TRUE(m.at(kCentral).live);
  ASSERT_EQ(m.records().size(), 1u);
  EXPECT_EQ(m.records()[0].event, "lost (DDS liveliness)");
  EXPECT_DOUBLE_EQ(m.records()[0].t_s, 2.5);
  m.on_liveliness_lost(Role::kCentral, writer(9));
  EXPECT_FALSE(m.at(kCentral).live);
}

TEST_F(PlantMembership, LivelinessLossOfAnOldWriterAfterARestartIsIgnored) {
  m.on_answer(kL1, writer(1));
  m.on_launcher(1, LauncherEvent::kDied, "L1");
  m.on_launcher(2, LauncherEvent::kStarted, "L1");
  EXPECT_TRUE(m.at(kL1).live);
  EXPECT_TRUE(m.at(kL1).rejoining);
  EXPECT_FALSE(m.at(kL1).writer_known);
  // The old process's lease expires before the new one answers: no effect.
  m.on_liveliness_lost(Role::kAgent, writer(1));
  EXPECT_TRUE(m.at(kL1).live);
  m.on_answer(kL1, writer(2));
  m.on_liveliness_lost(Role::kAgent, writer(1));  // late report of the old writer
  EXPECT_TRUE(m.at(kL1).live);
  m.on_liveliness_lost(Role::kAgent, writer(2));  // the new writer
  EXPECT_FALSE(m.at(kL1).live);
  std::vector<std::string> events;
  for (const auto& r : m.records()) events.push_back(r.event);
  EXPECT_EQ(events, (std::vector<std::string>{"died (launcher)", "started (launcher)", "rejoined",
                                              "lost (DDS liveliness)"}));
}

TEST_F(PlantMembership, UnsetWriterHandleMatchesNoKnownWriter) {
  WriterId zero;  // all-zero bytes, never set
  WriterId zero_set;
  zero_set.set = true;
  m.on_answer(kL1, zero_set);
  m.on_liveliness_lost(Role::kAgent, zero);
  EXPECT_TRUE(m.at(kL1).live);
}

TEST_F(PlantMembership, RejoinIsRecordedOnce) {
  m.begin_tick();
  EXPECT_EQ(m.on_deadline(), 2 * kPerSide);  // nobody answered: every agent declared dead
  EXPECT_FALSE(m.at(kGroupL).live);
  const std::size_t deaths = m.records().size();
  EXPECT_EQ(deaths, 2u * kPerSide + 3u);
  m.set_time(1.0);
  m.on_answer(kR2, writer(4));
  m.begin_tick();
  m.on_answer(kR2, writer(4));
  EXPECT_TRUE(m.at(kR2).live);
  ASSERT_EQ(m.records().size(), deaths + 1);
  EXPECT_EQ(m.records().back().name, "R2");
  EXPECT_EQ(m.records().back().event, "rejoined");
  EXPECT_DOUBLE_EQ(m.records().back().t_s, 1.0);
}

TEST_F(PlantMembership, StartedMemberIsRecordedAsRejoinedWhenItAnswers) {
  m.on_launcher(1, LauncherEvent::kStarted, "group-L");  // restarted before anyone saw it die
  ASSERT_EQ(m.records().size(), 1u);
  EXPECT_EQ(m.records()[0].event, "started (launcher)");
  m.on_answer(kGroupL, writer(3));
  ASSERT_EQ(m.records().size(), 2u);
  EXPECT_EQ(m.records()[1].event, "rejoined");
  EXPECT_FALSE(m.at(kGroupL).rejoining);
}

TEST_F(PlantMembership, DeadlineDeclaresOnlyLiveLateMembers) {
  m.begin_tick();
  for (const auto& id : m.all())
    if (!(id == kR2) && !(id == kCentral)) m.on_answer(id, writer(1));
  m.on_launcher(1, LauncherEvent::kDied, "central");
  EXPECT_EQ(m.on_deadline(), 1);
  EXPECT_FALSE(m.at(kR2).live);
  EXPECT_EQ(m.records().back().name, "R2");
  EXPECT_EQ(m.records().back().event, "missed the tick deadline");
  EXPECT_EQ(m.records().size(), 2u);  // central's death, R2's deadline
}

}  // namespace

TEST_F(PlantMembership, PausedMemberIsOutMarkedInTheMaskAndItsLeaseLossIsNoNews) {
  m.on_answer(kL1, writer(1));
  m.set_time(5.0);
  m.on_launcher(1, LauncherEvent::kPaused, "L1");
  EXPECT_FALSE(m.at(kL1).live);
  EXPECT_TRUE(m.at(kL1).paused);
  EXPECT_EQ(m.live_mask(0), (std::vector<uint8_t>{1, 0, 1, 1}));
  std::vector<uint8_t> paused(2 * kPerSide + 3, 0);
  paused[1] = 1;  // L1: agents L0.., R0.., then group-L, group-R, central
  EXPECT_EQ(m.paused_mask(), paused);
  // Its lease runs out during the pause; a late reply sent before the pause is no rejoin.
  m.on_liveliness_lost(Role::kAgent, writer(1));
  m.on_answer(kL1, writer(1));
  EXPECT_FALSE(m.at(kL1).live);
  ASSERT_EQ(m.records().size(), 1u);
  EXPECT_EQ(m.records()[0].event, "paused (launcher)");
  EXPECT_DOUBLE_EQ(m.records()[0].t_s, 5.0);
  // Not waited for at the deadline either.
  m.begin_tick();
  m.on_deadline();
  EXPECT_EQ(m.records()[1].name, "L0");
}

TEST_F(PlantMembership, ResumedMemberKeepsItsWriterAndRejoinsWhenItAnswers) {
  m.on_answer(kGroupL, writer(3));
  m.set_time(5.0);
  m.on_launcher(1, LauncherEvent::kPaused, "group-L");
  m.set_time(8.0);
  m.on_launcher(2, LauncherEvent::kResumed, "group-L");
  EXPECT_TRUE(m.at(kGroupL).live);
  EXPECT_TRUE(m.at(kGroupL).rejoining);
  EXPECT_FALSE(m.at(kGroupL).paused);
  EXPECT_TRUE(m.at(kGroupL).writer_known);
  EXPECT_EQ(m.paused_mask(), std::vector<uint8_t>(2 * kPerSide + 3, 0));
  // The lease loss of the pause, reported late, does not end the rejoin.
  m.on_liveliness_lost(Role::kGroup, writer(3));
  EXPECT_TRUE(m.at(kGroupL).live);
  m.set_time(8.01);
  m.on_answer(kGroupL, writer(3));
  std::vector<std::string> events;
  for (const auto& r : m.records()) events.push_back(r.event + "@" + std::to_string(r.t_s).substr(0, 4));
  EXPECT_EQ(events,
            (std::vector<std::string>{"paused (launcher)@5.00", "resumed (launcher)@8.00", "rejoined@8.01"}));
  // Once back, a lost lease ends it again.
  m.on_liveliness_lost(Role::kGroup, writer(3));
  EXPECT_FALSE(m.at(kGroupL).live);
}

TEST_F(PlantMembership, ResumeWithoutPauseChangesNothingAndAKillEndsAPause) {
  m.on_launcher(1, LauncherEvent::kResumed, "central");
  EXPECT_TRUE(m.records().empty());
  EXPECT_FALSE(m.at(kCentral).rejoining);
  m.on_launcher(2, LauncherEvent::kPaused, "R2");
  m.on_launcher(3, LauncherEvent::kDied, "R2");  // killed while paused: no longer paused
  EXPECT_FALSE(m.at(kR2).paused);
  EXPECT_FALSE(m.at(kR2).live);
  m.on_launcher(4, LauncherEvent::kResumed, "R2");  // too late: nothing to resume
  EXPECT_FALSE(m.at(kR2).live);
  ASSERT_EQ(m.records().size(), 2u);
  EXPECT_EQ(m.records()[1].event, "died (launcher)");
}

TEST_F(PlantMembership, AControllerHasOneWriterBetweenTwoStarts) {
  // group-L answers on writer 1; a copy of it on writer 2 (stranded on a host cut off, heard
  // again after the heal) is not taken; after the launcher announces a start, the first answer's
  // writer is the one.
  m.begin_tick();
  EXPECT_TRUE(m.takes(kGroupL, writer(1))) << "nothing heard yet: any writer of group-L";
  m.on_answer(kGroupL, writer(1));
  EXPECT_TRUE(m.takes(kGroupL, writer(1)));
  EXPECT_FALSE(m.takes(kGroupL, writer(2)));
  ASSERT_TRUE(m.on_launcher(1, LauncherEvent::kDied, "group-L"));
  EXPECT_FALSE(m.takes(kGroupL, writer(2))) << "a death alone names no new writer";
  ASSERT_TRUE(m.on_launcher(2, LauncherEvent::kStarted, "group-L"));
  m.begin_tick();
  EXPECT_TRUE(m.takes(kGroupL, writer(3)));
  m.on_answer(kGroupL, writer(3));
  EXPECT_FALSE(m.takes(kGroupL, writer(1))) << "the earlier copy";
  EXPECT_TRUE(m.takes(kGroupL, writer(3)));
}

TEST_F(PlantMembership, ARestartedControllerIsTheParticipantTheLauncherNamed) {
  // The launcher says which participant the new start of group-L is (57): an earlier copy (17)
  // that answers first is not it, and the new one is taken whenever it comes.
  m.begin_tick();
  m.on_answer(kGroupL, writer(1));
  ASSERT_TRUE(m.on_launcher(1, LauncherEvent::kStarted, "group-L", 57));
  m.begin_tick();
  EXPECT_FALSE(m.takes(kGroupL, writer(1), 17)) << "the earlier copy, though it would answer first";
  EXPECT_TRUE(m.takes(kGroupL, writer(2), 57));
  m.on_answer(kGroupL, writer(2));
  EXPECT_FALSE(m.takes(kGroupL, writer(1), 17));
  // Not said (0: the discovery server's id, never a controller's): the first writer's rule.
  ASSERT_TRUE(m.on_launcher(2, LauncherEvent::kStarted, "central", 0));
  EXPECT_TRUE(m.takes(kCentral, writer(5), 99));
}
