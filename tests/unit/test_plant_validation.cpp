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
  return r;
}

msg::GroupStatus status() {
  msg::GroupStatus g;
  g.tick(7);
  g.side(msg::SIDE_L);
  g.active(std::vector<uint8_t>{1, 0, 1, 0});
  return g;
}

msg::CentralCommand command() {
  msg::CentralCommand c;
  c.tick(7);
  c.phidot_ref({40.0, -40.0});
  return c;
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
