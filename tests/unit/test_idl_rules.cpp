// The rule of every message beside the IDL (idl/rules.hpp): the fields the plant's and the
// followers' tests do not already cover (PlantTick, Control, FaultGate, NodeReady).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "idl/rules.hpp"

namespace {

using namespace maptr;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

msg::FleetBounds bounds() {
  msg::FleetBounds b;
  b.per_side = 4;
  return b;
}

msg::PlantTick tick() {
  msg::PlantTick t;
  t.tick(5);
  t.central_stamp(-1);
  for (auto& s : t.sides()) {
    s.battery_V(24.0);
    s.active(std::vector<uint8_t>{1, 1, 0, 0});
    s.live(std::vector<uint8_t>(4, 1));
    s.wake(std::vector<uint8_t>{1, 1, 0, 1});
    s.n_active(2);
    s.relay_count(2);
    s.group_stamp(-1);
  }
  return t;
}

TEST(IdlRules, AWellFormedTickPasses) {
  EXPECT_TRUE(msg::well_formed(tick(), bounds()));
  auto t = tick();
  t.paused(std::vector<uint8_t>(2 * 4 + 3, 0));
  EXPECT_TRUE(msg::well_formed(t, bounds()));
}

TEST(IdlRules, TickMasksHaveOneEntryOfZeroOrOnePerAgent) {
  auto t = tick();
  t.sides()[0].wake()[2] = 7;
  EXPECT_FALSE(msg::well_formed(t, bounds()));
  t = tick();
  t.sides()[1].live().pop_back();
  EXPECT_FALSE(msg::well_formed(t, bounds()));
  t = tick();
  t.paused(std::vector<uint8_t>(2 * 4 + 2, 0));
  EXPECT_FALSE(msg::well_formed(t, bounds()));
  t.paused(std::vector<uint8_t>(2 * 4 + 3, 2));
  EXPECT_FALSE(msg::well_formed(t, bounds()));
}

TEST(IdlRules, TheDrivesMeasurementsAreAllAbsentOrOneFiniteEntryPerAgent) {
  auto measured = [] {
    auto t = tick();
    for (auto& s : t.sides()) {
      s.drove(std::vector<uint8_t>{1, 1, 0, 0});
      s.drive_V(std::vector<float>{3.0f, 3.0f, 0.0f, 0.0f});
      s.measured_A(std::vector<float>{0.2f, 0.2f, 0.0f, -0.1f});
      s.reported(std::vector<uint8_t>{1, 1, 1, 0});
      s.reported_A(std::vector<float>{0.2f, 0.2f, 0.0f, 0.0f});
    }
    return t;
  };
  EXPECT_TRUE(msg::well_formed(measured(), bounds()));
  auto t = measured();
  t.sides()[0].measured_A().pop_back();  // one entry short
  EXPECT_FALSE(msg::well_formed(t, bounds()));
  t = measured();
  t.sides()[1].reported_A()[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(msg::well_formed(t, bounds()));
  t = measured();
  t.sides()[1].drove()[3] = 2;
  EXPECT_FALSE(msg::well_formed(t, bounds()));
  t = measured();
  t.sides()[0].drive_V().clear();  // some present, some not
  EXPECT_FALSE(msg::well_formed(t, bounds()));
}

TEST(IdlRules, AGroupsFaultyFlagsAreAbsentOrAKnownDiagnosisPerAgent) {
  msg::GroupStatus g;
  g.side(msg::SIDE_L);
  g.active(std::vector<uint8_t>(4, 1));
  g.live(std::vector<uint8_t>(4, 1));
  g.ledger().wear_m(std::vector<double>(4, 0.0));
  g.ledger().active_time_s(std::vector<double>(g.ledger().wear_m().size(), 0.0));
  EXPECT_TRUE(msg::well_formed(g, bounds()));
  g.faulty(std::vector<uint8_t>{0, msg::DIAG_LIAR, 0, msg::DIAG_OPEN});
  EXPECT_TRUE(msg::well_formed(g, bounds()));
  g.faulty()[2] = msg::DIAG_LIAR + 1;
  EXPECT_FALSE(msg::well_formed(g, bounds()));
  g.faulty(std::vector<uint8_t>(3, 0));
  EXPECT_FALSE(msg::well_formed(g, bounds()));
}

TEST(IdlRules, TickNumbersAndStamps) {
  for (double bad : {kNaN, kInf}) {
    auto t = tick();
    t.t(bad);
    EXPECT_FALSE(msg::well_formed(t, bounds())) << "t " << bad;
  }
  auto t = tick();
  t.central_stamp(-2);
  EXPECT_FALSE(msg::well_formed(t, bounds()));
  t = tick();
  t.sides()[0].group_stamp(-5);
  EXPECT_FALSE(msg::well_formed(t, bounds()));
  t = tick();
  t.sides()[1].phidot_ref_prev(kNaN);
  EXPECT_FALSE(msg::well_formed(t, bounds()));
  t = tick();
  t.run_state(static_cast<msg::RunState>(msg::RUN_ABORTED + 1));
  EXPECT_FALSE(msg::well_formed(t, bounds()));
}

TEST(IdlRules, ControlNeedsAKnownCommandAndANumber) {
  msg::Control c;
  c.command(msg::CONTROL_START);
  c.seq(1);
  EXPECT_TRUE(msg::well_formed(c));
  c.seq(0);
  EXPECT_FALSE(msg::well_formed(c));
  c.seq(2);
  c.command(msg::CONTROL_NONE);  // a default sample
  EXPECT_FALSE(msg::well_formed(c));
  c.command(static_cast<msg::ControlCommand>(msg::CONTROL_GATE_OPEN + 1));
  EXPECT_FALSE(msg::well_formed(c));
}

TEST(IdlRules, FaultGateTimeIsFiniteAndNotNegative) {
  msg::FaultGate g;
  g.tick(100);
  g.t(1.0);
  EXPECT_TRUE(msg::well_formed(g));
  for (double bad : {kNaN, kInf, -kInf, -1.0}) {
    g.t(bad);
    EXPECT_FALSE(msg::well_formed(g)) << bad;
  }
}

TEST(IdlRules, NodeReadyNamesAProcessOfKnownKindWithAPid) {
  msg::NodeReady r;
  r.name("L3");
  r.kind(msg::NODE_AGENT);
  r.pid(1234);
  r.ready(true);
  EXPECT_TRUE(msg::well_formed(r));
  r.pid(0);
  EXPECT_FALSE(msg::well_formed(r));
  r.pid(1234);
  r.kind(static_cast<msg::NodeKind>(msg::NODE_PLANT + 1));
  EXPECT_FALSE(msg::well_formed(r));
  r.kind(msg::NODE_AGENT);
  r.name("");
  EXPECT_FALSE(msg::well_formed(r));
  r.name(std::string(msg::kMaxNameLength + 1, 'x'));
  EXPECT_FALSE(msg::well_formed(r));
}

TEST(IdlRules, NodeReadyNamesItsUnmatchedOnlyWhileNotReadyAndBounded) {
  msg::NodeReady r;
  r.name("plant");
  r.kind(msg::NODE_PLANT);
  r.pid(1234);
  r.ready(false);
  r.unmatched({"R10", "group-L"});
  EXPECT_TRUE(msg::well_formed(r));
  r.ready(true);  // a ready process misses nobody
  EXPECT_FALSE(msg::well_formed(r));
  r.ready(false);
  r.unmatched({"R10", ""});
  EXPECT_FALSE(msg::well_formed(r));
  r.unmatched(std::vector<std::string>(msg::kMaxUnmatched, "R10"));
  EXPECT_TRUE(msg::well_formed(r));
  r.unmatched().push_back("R11");
  EXPECT_FALSE(msg::well_formed(r));
}

}  // namespace
