// The group controller's wire adapter (group/group_wire.hpp): a tick read as the core's input for
// one side, and a decision answered as GroupStatus and logged as a Level-2 record.
#include <gtest/gtest.h>

#include "comm/lockstep/wear_ledger.hpp"
#include "group/group_wire.hpp"

namespace {

namespace msg = maptr::msg;
using maptr::control::GroupDecision;
using maptr::control::GroupInput;

/// A tick whose two sides differ in every field the group reads; side R carries measurements.
msg::PlantTick two_sided_tick() {
  msg::PlantTick t;
  t.tick(42);
  t.t(0.42);
  t.v_x(1.5);
  t.w(0.25);
  for (int s = 0; s < 2; ++s) {
    msg::SideTick& side = t.sides()[s];
    side.phidot(40.0 + s);
    side.phidot_prev(39.0 + s);
    side.phidot_ref(41.0 + 10 * s);
    side.battery_V(23.0 + s);
    side.live({1, 1, static_cast<uint8_t>(s), 1});
    side.active({1, 0, 0, static_cast<uint8_t>(s)});
    side.relay_count(static_cast<uint16_t>(2 + s));
  }
  msg::SideTick& r = t.sides()[msg::SIDE_R];
  r.measured_A({0.5, 0.0, 0.0, 1.5});
  r.drive_V({6.0, 0.0, 0.0, 7.0});
  r.drove({1, 0, 0, 1});
  r.reported({1, 0, 0, 0});
  r.reported_A({0.5, 0.0, 0.0, 0.0});
  return t;
}

TEST(GroupWire, EachSideReadsItsOwnFieldsAndBothReferences) {
  const msg::PlantTick t = two_sided_tick();
  const GroupInput l = maptr::group::group_input(t, 0), r = maptr::group::group_input(t, 1);
  EXPECT_EQ(l.tick, 42);
  EXPECT_DOUBLE_EQ(l.t, 0.42);
  EXPECT_DOUBLE_EQ(l.v_x, 1.5);
  EXPECT_DOUBLE_EQ(l.w, 0.25);
  EXPECT_DOUBLE_EQ(l.phidot_side, 40.0);
  EXPECT_DOUBLE_EQ(r.phidot_side, 41.0);
  EXPECT_DOUBLE_EQ(l.phidot_ref_L, 41.0);
  EXPECT_DOUBLE_EQ(l.phidot_ref_R, 51.0);
  EXPECT_DOUBLE_EQ(r.phidot_ref_L, 41.0);
  EXPECT_DOUBLE_EQ(r.battery_V, 24.0);
  EXPECT_EQ(l.live, (std::vector<uint8_t>{1, 1, 0, 1}));
  EXPECT_EQ(r.active, (std::vector<uint8_t>{1, 0, 0, 1}));
  EXPECT_EQ(l.n_other, 2);
  EXPECT_EQ(r.n_other, 3);
  EXPECT_FALSE(l.measured);  // no measurements on side L
  ASSERT_TRUE(r.measured);
  ASSERT_EQ(r.drives.agents.size(), 4u);
  EXPECT_DOUBLE_EQ(r.drives.phidot_prev, 40.0);
  EXPECT_TRUE(r.drives.agents[3].drove);
  EXPECT_DOUBLE_EQ(r.drives.agents[3].drive_V, 7.0);
  EXPECT_DOUBLE_EQ(r.drives.agents[3].measured_A, 1.5);
  EXPECT_FALSE(r.drives.agents[3].reported);
  EXPECT_TRUE(r.drives.agents[0].reported);
}

TEST(GroupWire, TheStatusCarriesTheDecisionAndTheLevel2Outcome) {
  const msg::PlantTick t = two_sided_tick();
  const GroupInput in = maptr::group::group_input(t, 1);
  GroupDecision d;
  d.active = {1, 0, 0, 1};
  d.n_active = 2;
  d.n_live = 3;
  d.level2.status = maptr::control::kL2Infeasible;
  d.level2.relaxed = 2.5;
  d.level2.oracle_n_active = -1;
  d.level2.solve_ms = 1.25;
  d.decisions = 7;
  d.reallocations = 3;
  d.faulty = {0, 0, 2, 0};
  maptr::control::Ledger ledger(4);
  ledger.wear_m = {1.0, 2.0, 3.0, 4.0};
  ledger.decisions = 7;
  ledger.reallocations = 3;
  const msg::GroupStatus st = maptr::group::group_status(t, 1, in, d, ledger);
  EXPECT_EQ(st.tick(), 42u);
  EXPECT_EQ(st.side(), msg::SIDE_R);
  EXPECT_EQ(st.active(), d.active);
  EXPECT_EQ(st.live(), in.live);
  EXPECT_EQ(st.ledger().wear_m(), ledger.wear_m);
  EXPECT_EQ(st.n_active(), 2);
  EXPECT_EQ(st.n_live(), 3);
  EXPECT_EQ(st.n_other(), 3);
  EXPECT_EQ(st.level2_status(), msg::L2_INFEASIBLE);
  EXPECT_DOUBLE_EQ(st.level2_relaxed(), 2.5);
  EXPECT_EQ(st.oracle_n_active(), -1);
  EXPECT_DOUBLE_EQ(st.solve_time_ms(), 1.25);
  EXPECT_EQ(st.ledger().decisions(), 7u);
  EXPECT_EQ(st.ledger().reallocations(), 3u);
  EXPECT_EQ(st.faulty(), d.faulty);
  for (const auto& [core, wire] : {std::pair{maptr::control::kL2None, msg::L2_NONE},
                                   {maptr::control::kL2Ok, msg::L2_OK},
                                   {maptr::control::kL2Failed, msg::L2_SOLVER_FAILED}}) {
    d.level2.status = core;
    EXPECT_EQ(maptr::group::group_status(t, 1, in, d, ledger).level2_status(), wire);
  }
  d.level2.status = maptr::control::kL2Failed + 1;  // no status of the core: none on the wire
  EXPECT_EQ(maptr::group::group_status(t, 1, in, d, ledger).level2_status(), msg::L2_NONE);
}

TEST(GroupWire, TheDecisionAStatusCarriesIsReadBackAsTheCoresRecord) {
  const msg::PlantTick t = two_sided_tick();
  const auto in = maptr::group::group_input(t, 1);
  maptr::control::GroupDecision d;
  d.active = {1, 0, 0, 1};
  d.n_active = 2;
  d.n_live = 3;
  d.level2.status = maptr::control::kL2Ok;
  d.level2.relaxed = 2.25;
  d.level2.oracle_n_active = 2;
  d.level2.solve_ms = 0.75;
  maptr::control::Ledger ledger(4);
  const auto back = maptr::group::level2_of(maptr::group::group_status(t, 1, in, d, ledger));
  EXPECT_EQ(back.status, maptr::control::kL2Ok);
  EXPECT_DOUBLE_EQ(back.relaxed, 2.25);
  EXPECT_EQ(back.oracle_n_active, 2);
  EXPECT_DOUBLE_EQ(back.solve_ms, 0.75);
  EXPECT_EQ(back.n_live, 3);
  EXPECT_EQ(back.n_target, 2);
  EXPECT_STREQ(maptr::control::level2_status_name(back.status), "ok");
}

}  // namespace

TEST(GroupWire, ARestartedGroupFindsTheLedgerTheTickCarriesForItsOwnStartOnly) {
  maptr::control::Ledger ledger(4);
  ledger.wear_m = {1.5, 0.0, 2.25, 0.125};
  ledger.active_time_s = {0.5, 0.0, 1.0, 0.0};
  ledger.last_t = 12.34;
  ledger.last_alloc_t = 10.0;
  ledger.n_target = 2;
  ledger.assignment = {1, 0, 1, 0};
  ledger.decisions = 9;
  ledger.reallocations = 4;
  msg::PlantTick t = two_sided_tick();
  EXPECT_FALSE(maptr::group::kept_ledger(t, 1, 77));  // a tick without a hand-over
  msg::KeptLedger k;
  k.side(msg::SIDE_R);
  k.for_participant(77);
  k.assignment(ledger.assignment);
  k.ledger(maptr::comm::to_msg(ledger));
  t.ledgers().push_back(k);
  const auto back = maptr::group::kept_ledger(t, 1, 77);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->wear_m, ledger.wear_m);
  EXPECT_EQ(back->active_time_s, ledger.active_time_s);
  EXPECT_EQ(back->last_t, ledger.last_t);
  EXPECT_EQ(back->last_alloc_t, ledger.last_alloc_t);
  EXPECT_EQ(back->n_target, 2);
  EXPECT_EQ(back->assignment, ledger.assignment);
  EXPECT_EQ(back->decisions, 9u);
  EXPECT_EQ(back->reallocations, 4u);
  EXPECT_FALSE(maptr::group::kept_ledger(t, 1, 78));  // another start of group-R (a stale copy)
  EXPECT_FALSE(maptr::group::kept_ledger(t, 0, 77));  // the other side
  t.ledgers()[0].for_participant(-1);                 // the plant was not told which start
  EXPECT_TRUE(maptr::group::kept_ledger(t, 1, 78));
}
