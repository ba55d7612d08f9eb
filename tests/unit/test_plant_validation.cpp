// Plant sample validation (plant/validation.hpp): pure checks on the IDL types.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "plant/validation.hpp"

namespace {

using namespace maptr;
using plant::check;
using plant::SampleLimits;
using plant::valid;
using plant::Verdict;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

SampleLimits limits() {
  SampleLimits l;
  l.per_side = 4;
  l.battery_V[0] = 23.4;
  l.battery_V[1] = 22.0;
  l.voltage_tolerance_V = 1e-9;
  l.ref_bound_radps = 1e4;
  return l;
}

msg::AgentReply reply() {
  msg::AgentReply r;
  r.tick(7);
  r.side(msg::SIDE_R);
  r.index(3);
  r.voltage_V(12.0);
  r.current_A(0.8);
  r.efficiency(0.6);
  r.state(msg::AGENT_ACTIVE);
  r.pid(4242);
  return r;
}

msg::GroupStatus status() {
  msg::GroupStatus g;
  g.tick(7);
  g.side(msg::SIDE_L);
  g.active(std::vector<uint8_t>{1, 0, 1, 0});
  g.live(std::vector<uint8_t>{1, 1, 1, 0});
  g.ledger().wear_m(std::vector<double>{12.5, 0.0, 11.0, 3.0});
  g.ledger().active_time_s(std::vector<double>(g.ledger().wear_m().size(), 0.0));
  g.n_active(2);
  g.n_live(3);
  g.n_other(4);
  g.level2_status(msg::L2_OK);
  g.level2_relaxed(2.4);
  g.oracle_n_active(2);
  g.solve_time_ms(1.7);
  return g;
}

msg::CentralCommand command() {
  msg::CentralCommand c;
  c.tick(7);
  c.phidot_ref({40.0, -40.0});
  c.v_x_ref(0.8);
  c.w_ref(-0.2);
  return c;
}

msg::MembershipEvent event(const std::string& name, msg::NodeKind kind, msg::Side side, uint16_t index) {
  msg::MembershipEvent e;
  e.seq(3);
  e.name(name);
  e.node_kind(kind);
  e.side(side);
  e.index(index);
  e.kind(msg::MEMBER_DIED);
  e.wall_s(4.5);
  return e;
}

TEST(PlantValidation, WellFormedSamplesPass) {
  EXPECT_TRUE(valid(reply(), limits()));
  EXPECT_TRUE(valid(status(), limits()));
  EXPECT_TRUE(valid(command(), limits()));
}

TEST(PlantValidation, AgentReplyNotFiniteIsMalformed) {
  for (double bad : {kNaN, kInf, -kInf}) {
    auto r = reply();
    r.voltage_V(bad);
    EXPECT_FALSE(valid(r, limits())) << bad;
    r = reply();
    r.current_A(bad);
    EXPECT_FALSE(valid(r, limits())) << bad;
    r = reply();
    r.efficiency(bad);
    EXPECT_FALSE(valid(r, limits())) << bad;
  }
}

TEST(PlantValidation, AgentReplyOutOfRangeIsMalformed) {
  auto r = reply();
  r.side(static_cast<msg::Side>(2));
  EXPECT_FALSE(valid(r, limits()));
  r = reply();
  r.index(4);  // == per side
  EXPECT_FALSE(valid(r, limits()));
  r.index(65535);
  EXPECT_FALSE(valid(r, limits()));
  r = reply();
  r.state(static_cast<msg::AgentState>(msg::AGENT_STOPPING + 1));
  EXPECT_FALSE(valid(r, limits()));
  r = reply();
  r.voltage_V(-1e-6);
  EXPECT_FALSE(valid(r, limits()));
}

TEST(PlantValidation, AgentVoltageIsBoundedByItsSidesBattery) {
  auto r = reply();  // right side: 22.0 V
  r.voltage_V(22.0);
  EXPECT_TRUE(valid(r, limits()));
  r.voltage_V(22.0 + 1e-6);
  EXPECT_FALSE(valid(r, limits()));
  r.side(msg::SIDE_L);  // left side: 23.4 V
  EXPECT_TRUE(valid(r, limits()));
  r.voltage_V(23.5);
  EXPECT_FALSE(valid(r, limits()));
}

TEST(PlantValidation, DrivingStates) {
  auto r = reply();
  for (msg::AgentState s : {msg::AGENT_ACTIVE, msg::AGENT_HOLDING, msg::AGENT_STOPPING}) {
    r.state(s);
    EXPECT_TRUE(plant::drives(r)) << int(s);
  }
  for (msg::AgentState s : {msg::AGENT_IDLE, msg::AGENT_COASTING}) {
    r.state(s);
    EXPECT_FALSE(plant::drives(r)) << int(s);
  }
}

TEST(PlantValidation, GroupStatusSideAndMaskLength) {
  auto g = status();
  g.side(static_cast<msg::Side>(2));
  EXPECT_FALSE(valid(g, limits()));
  g = status();
  g.active(std::vector<uint8_t>{1, 0, 1});
  EXPECT_FALSE(valid(g, limits()));
  g.active(std::vector<uint8_t>{1, 0, 1, 0, 1});
  EXPECT_FALSE(valid(g, limits()));
  g.active({});
  EXPECT_FALSE(valid(g, limits()));
}

TEST(PlantValidation, GroupStatusLiveMaskAndLedgerHaveOneEntryPerAgent) {
  auto g = status();
  g.live(std::vector<uint8_t>{1, 1, 1});
  EXPECT_FALSE(valid(g, limits()));
  g.live(std::vector<uint8_t>{1, 1, 1, 1, 1});
  EXPECT_FALSE(valid(g, limits()));
  g = status();
  g.ledger().wear_m(std::vector<double>{1.0, 2.0, 3.0});
  g.ledger().active_time_s(std::vector<double>(g.ledger().wear_m().size(), 0.0));
  EXPECT_FALSE(valid(g, limits()));
  g.ledger().wear_m({});
  g.ledger().active_time_s(std::vector<double>(g.ledger().wear_m().size(), 0.0));
  EXPECT_FALSE(valid(g, limits()));
  // A mask entry is 0 or 1.
  g = status();
  g.active()[1] = 2;
  EXPECT_FALSE(valid(g, limits()));
  g = status();
  g.live()[0] = 255;
  EXPECT_FALSE(valid(g, limits()));
}

TEST(PlantValidation, GroupStatusWearIsAFiniteDistance) {
  for (double bad : {kNaN, kInf, -kInf, -0.001}) {
    auto g = status();
    g.ledger().wear_m()[2] = bad;
    EXPECT_FALSE(valid(g, limits())) << bad;
  }
}

TEST(PlantValidation, GroupStatusCountsAboveASideAreMalformed) {
  auto g = status();
  g.n_active(4);
  g.n_live(4);
  g.n_other(4);
  EXPECT_TRUE(valid(g, limits()));
  g.n_active(5);
  EXPECT_FALSE(valid(g, limits()));
  g = status();
  g.n_live(5);
  EXPECT_FALSE(valid(g, limits()));
  g = status();
  g.n_other(65535);
  EXPECT_FALSE(valid(g, limits()));
}

TEST(PlantValidation, GroupStatusLevel2Fields) {
  auto g = status();
  g.level2_status(static_cast<msg::Level2Status>(msg::L2_SOLVER_FAILED + 1));
  EXPECT_FALSE(valid(g, limits()));
  for (double bad : {kNaN, kInf, -0.1, 4.1}) {
    g = status();
    g.level2_relaxed(bad);
    EXPECT_FALSE(valid(g, limits())) << "relaxed " << bad;
  }
  for (int16_t bad : {int16_t{-2}, int16_t{5}}) {
    g = status();
    g.oracle_n_active(bad);
    EXPECT_FALSE(valid(g, limits())) << "oracle " << bad;
  }
  g = status();
  g.oracle_n_active(-1);  // not run
  EXPECT_TRUE(valid(g, limits()));
  for (double bad : {kNaN, kInf, -1.0}) {
    g = status();
    g.solve_time_ms(bad);
    EXPECT_FALSE(valid(g, limits())) << "solve time " << bad;
  }
}

TEST(PlantValidation, CentralSpeedAndYawReferencesFiniteAndBounded) {
  for (double bad : {kNaN, kInf, -kInf, 1e2, -1e2, 1e9}) {
    auto c = command();
    c.v_x_ref(bad);
    EXPECT_FALSE(valid(c, limits())) << "v_x_ref " << bad;
    c = command();
    c.w_ref(bad);
    EXPECT_FALSE(valid(c, limits())) << "w_ref " << bad;
  }
  auto c = command();
  c.v_x_ref(-99.0);
  c.w_ref(99.0);
  EXPECT_TRUE(valid(c, limits()));
}

TEST(PlantValidation, AnAgentReplyWithoutAPidIsMalformed) {
  auto r = reply();
  r.pid(0);
  EXPECT_FALSE(valid(r, limits()));
}

TEST(PlantValidation, AMembershipEventDescribesTheProcessItNames) {
  const auto lim = limits();
  EXPECT_TRUE(valid(event("L3", msg::NODE_AGENT, msg::SIDE_L, 3), lim));
  EXPECT_TRUE(valid(event("R0", msg::NODE_AGENT, msg::SIDE_R, 0), lim));
  EXPECT_TRUE(valid(event("group-R", msg::NODE_GROUP, msg::SIDE_R, 0), lim));
  EXPECT_TRUE(valid(event("central", msg::NODE_CENTRAL, msg::SIDE_L, 0), lim));
  EXPECT_TRUE(valid(event("plant", msg::NODE_PLANT, msg::SIDE_L, 0), lim));
  EXPECT_FALSE(valid(event("L3", msg::NODE_AGENT, msg::SIDE_L, 2), lim));       // another index
  EXPECT_FALSE(valid(event("L3", msg::NODE_AGENT, msg::SIDE_R, 3), lim));       // another side
  EXPECT_FALSE(valid(event("L3", msg::NODE_GROUP, msg::SIDE_L, 3), lim));       // another kind
  EXPECT_FALSE(valid(event("L4", msg::NODE_AGENT, msg::SIDE_L, 4), lim));       // beyond the side
  EXPECT_FALSE(valid(event("group-L", msg::NODE_GROUP, msg::SIDE_R, 0), lim));  // the other side
  EXPECT_FALSE(valid(event("nobody", msg::NODE_AGENT, msg::SIDE_L, 0), lim));
  EXPECT_FALSE(valid(event("", msg::NODE_CENTRAL, msg::SIDE_L, 0), lim));
  auto e = event("L1", msg::NODE_AGENT, msg::SIDE_L, 1);
  e.seq(0);
  EXPECT_FALSE(valid(e, lim));
  e = event("group-L", msg::NODE_GROUP, msg::SIDE_L, 0);
  e.kind(msg::MEMBER_STARTED);
  e.participant_id(65535);
  EXPECT_TRUE(valid(e, lim));
  e.participant_id(65536);  // no participant id is that large
  EXPECT_FALSE(valid(e, lim));
  e.participant_id(-2);
  EXPECT_FALSE(valid(e, lim));
  e = event("L1", msg::NODE_AGENT, msg::SIDE_L, 1);
  e.kind(static_cast<msg::MemberEvent>(msg::MEMBER_RESUMED + 1));
  EXPECT_FALSE(valid(e, lim));
  e = event("L1", msg::NODE_AGENT, msg::SIDE_L, 1);
  e.wall_s(kNaN);
  EXPECT_FALSE(valid(e, lim));
  e = event("L1", msg::NODE_AGENT, msg::SIDE_L, 1);
  e.name(std::string(65, 'L'));
  EXPECT_FALSE(valid(e, lim));
}

TEST(PlantValidation, OneAnswerPerSenderAndTick) {
  plant::OncePerTick<msg::GroupStatus> once;
  auto g = status();
  EXPECT_EQ(once.see(g, 7), plant::Once::kFirst);
  // The same answer again (a resent tick), its count of rejected samples grown: a copy.
  g.rejected(5);
  EXPECT_EQ(once.see(g, 7), plant::Once::kCopy);
  // A different answer for the same tick: a conflict, every time, and the first stays.
  auto other = status();
  other.ledger().wear_m()[0] = 1.0;  // a ledger going backwards
  EXPECT_EQ(once.see(other, 7), plant::Once::kConflict);
  EXPECT_EQ(once.see(other, 7), plant::Once::kConflict);
  EXPECT_EQ(once.see(status(), 7), plant::Once::kCopy);
  // The next tick's first answer.
  EXPECT_EQ(once.see(other, 8), plant::Once::kFirst);
}

TEST(PlantValidation, OneCentralCommandPerTick) {
  plant::OncePerTick<msg::CentralCommand> once;
  EXPECT_EQ(once.see(command(), 7), plant::Once::kFirst);
  auto absurd = command();
  absurd.phidot_ref()[0] = 0.0;  // well-formed, but not the command already taken
  EXPECT_EQ(once.see(absurd, 7), plant::Once::kConflict);
}

TEST(PlantValidation, CentralReferenceFiniteAndBounded) {
  for (double bad : {kNaN, kInf, -kInf, 1e4, -1e4}) {
    for (int s = 0; s < 2; ++s) {
      auto c = command();
      c.phidot_ref()[s] = bad;
      EXPECT_FALSE(valid(c, limits())) << bad << " on side " << s;
    }
  }
  auto c = command();
  c.phidot_ref()[msg::SIDE_L] = 9999.0;
  EXPECT_TRUE(valid(c, limits()));
}

TEST(PlantValidation, ARelayedCountAboveASideIsMalformed) {
  auto c = command();
  c.relay_count_for({4, 0});  // 4 per side: every agent of the other side active
  EXPECT_TRUE(valid(c, limits()));
  for (int s = 0; s < 2; ++s) {
    c = command();
    c.relay_count_for()[s] = 5;
    EXPECT_FALSE(valid(c, limits())) << "side " << s;
  }
}

TEST(PlantValidation, MembershipEventKindsMapToTheMembershipsEvents) {
  EXPECT_EQ(plant::launcher_event(msg::MEMBER_DIED), plant::LauncherEvent::kDied);
  EXPECT_EQ(plant::launcher_event(msg::MEMBER_STARTED), plant::LauncherEvent::kStarted);
  EXPECT_EQ(plant::launcher_event(static_cast<msg::MemberEvent>(9)), plant::LauncherEvent::kOther);
}

TEST(PlantValidation, OnlyTheCurrentTickCounts) {
  EXPECT_EQ(check(reply(), limits(), 7), Verdict::kAccepted);
  EXPECT_EQ(check(reply(), limits(), 8), Verdict::kOtherTick);
  EXPECT_EQ(check(reply(), limits(), 6), Verdict::kOtherTick);
  EXPECT_EQ(check(status(), limits(), 8), Verdict::kOtherTick);
  EXPECT_EQ(check(command(), limits(), 8), Verdict::kOtherTick);
  auto r = reply();
  r.voltage_V(kNaN);
  EXPECT_EQ(check(r, limits(), 7), Verdict::kMalformed);
  EXPECT_EQ(check(r, limits(), 8), Verdict::kMalformed);  // malformed whatever its tick
}

TEST(PlantValidation, TheBatteryBoundsTheVoltageOfTheTickAnsweredOnly) {
  // Full duty at tick 6 on a battery that has since sagged to 22.0 V: the copy that arrives
  // at tick 7 (a follower answered a resent tick 6 again) is a copy, not a malformed sample.
  auto r = reply();  // right side: 22.0 V now
  r.tick(6);
  r.voltage_V(22.0 + 1e-3);
  EXPECT_EQ(check(r, limits(), 7), Verdict::kOtherTick);
  EXPECT_TRUE(plant::repeated(check(r, limits(), 7), r.tick(), 7));
  // The same voltage answering the current tick is more than the battery gives now.
  r.tick(7);
  EXPECT_EQ(check(r, limits(), 7), Verdict::kMalformed);
}

TEST(PlantValidation, AnAnswerOneTickOldIsACopyOlderIsLateNewerIsNeither) {
  // At tick 9: an answer to 8 is a copy after a repeated tick, one to 7 or before came late.
  EXPECT_TRUE(plant::repeated(Verdict::kOtherTick, 8, 9));
  EXPECT_FALSE(plant::late(Verdict::kOtherTick, 8, 9));
  EXPECT_TRUE(plant::late(Verdict::kOtherTick, 7, 9));
  EXPECT_TRUE(plant::late(Verdict::kOtherTick, 0, 9));
  EXPECT_FALSE(plant::repeated(Verdict::kOtherTick, 7, 9));
  // An answer to a tick not sent yet is neither: it stays a reject.
  EXPECT_FALSE(plant::late(Verdict::kOtherTick, 10, 9));
  EXPECT_FALSE(plant::repeated(Verdict::kOtherTick, 10, 9));
  // A malformed or forged sample is never late.
  EXPECT_FALSE(plant::late(Verdict::kMalformed, 7, 9));
  EXPECT_FALSE(plant::late(Verdict::kForged, 7, 9));
}

}  // namespace
