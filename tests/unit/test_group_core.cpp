// Group core (control/group_core.hpp): which agents of a side run. Default robot (16 agents,
// 8 per side, 13.2 kg, r = 0.035 m), left side, ticks of 10 ms. In steady cruise at 10 m/s the
// Level-2 oracle keeps 2 of the 8 agents, at 5 m/s 3 (checked below against the oracle itself).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "comm/lockstep/wear_ledger.hpp"
#include "control/group_core.hpp"
#include "records/ledger_file.hpp"

namespace {

using maptr::control::GroupConfig;
using maptr::control::GroupCore;
using maptr::control::GroupDecision;
using maptr::control::GroupInput;
using maptr::control::GroupMode;
using maptr::control::kL2None;
using Mask = std::vector<uint8_t>;

constexpr int kPerSide = 8;

GroupConfig ec() {
  GroupConfig c;
  c.oracle = true;
  c.t_on_s = 1000.0;       // Level 3 on T_ON only where a test asks for it
  c.level2_defer_s = 0.0;  // a decision applied in the tick whose inputs it used, unless a test asks
  return c;
}

/// Feeds a GroupCore one tick after the other; the assignment it returns is in force next tick.
struct Side {
  GroupCore core;
  GroupInput in;

  explicit Side(const GroupConfig& c, maptr::control::Level2Runner* runner = nullptr)
      : core(0, c, std::nullopt, runner) {
    in.live.assign(kPerSide, 1);
    in.active.assign(kPerSide, 0);
    in.battery_V = 23.4;
  }
  /// One tick with the body at speed v [m/s] and both wheel references at ref [m/s].
  GroupDecision step(double v, double ref) {
    const double r = 0.035;
    in.t = static_cast<double>(in.tick) * 0.01;
    in.v_x = v;
    in.phidot_side = v / r;
    in.phidot_ref_L = in.phidot_ref_R = ref / r;
    const GroupDecision d = core.step(in);
    in.active = d.active;
    ++in.tick;
    return d;
  }
  /// Ticks until time t [s] (exclusive) at v = ref; returns the last decision.
  GroupDecision cruise_until(double t, double v) {
    GroupDecision d;
    while (static_cast<double>(in.tick) * 0.01 < t - 1e-9) d = step(v, v);
    return d;
  }
};

Mask agents(std::initializer_list<int> on) {
  Mask m(kPerSide, 0);
  for (int j : on) m[j] = 1;
  return m;
}

TEST(GroupCore, ModeAllRunsEveryLiveAgent) {
  GroupConfig c = ec();
  c.mode = GroupMode::kAll;
  Side s(c);
  s.in.live[3] = 0;
  for (int k = 0; k < 300; ++k) {
    const GroupDecision d = s.step(10.0, 10.0);  // cruising: Level 2 would keep fewer
    ASSERT_EQ(d.active, s.in.live) << k;
    ASSERT_EQ(d.n_active, kPerSide - 1);
    ASSERT_FALSE(d.level2_ran);
    ASSERT_EQ(d.level2.status, kL2None);
  }
}

TEST(GroupCore, EveryLiveAgentRunsUntilNearTheReferenceThenLevel2Decides) {
  Side s(ec());
  for (int k = 0; k < 50; ++k) {  // starting: 50 % below the reference
    const GroupDecision d = s.step(5.0, 10.0);
    ASSERT_EQ(d.n_active, kPerSide);
    ASSERT_FALSE(d.level2_ran);
  }
  // 10 % below: inside the hysteresis band, but cruise has not been reached yet.
  EXPECT_EQ(s.step(9.0, 10.0).n_active, kPerSide);
  // 4 % below: cruise; Level 2 decides at once, as the oracle does (still accelerating, it may
  // keep them all).
  const GroupDecision entry = s.step(9.6, 10.0);
  ASSERT_TRUE(entry.level2_ran);
  EXPECT_EQ(entry.n_active, entry.level2.oracle_n_active);
  // At the reference, its next decision (1 s later) keeps fewer agents.
  GroupDecision d;
  while (!(d = s.step(10.0, 10.0)).level2_ran) ASSERT_EQ(d.n_active, entry.n_active);
  EXPECT_EQ(d.n_active, d.level2.oracle_n_active);
  EXPECT_LT(d.n_active, kPerSide);
  // 10 % below: still cruising (the hysteresis band); the count holds until the next decision.
  for (int k = 0; k < 50; ++k) EXPECT_EQ(s.step(9.0, 10.0).n_active, d.n_active);
  // 25 % below: out of cruise, every live agent runs again.
  EXPECT_EQ(s.step(7.5, 10.0).n_active, kPerSide);
}

TEST(GroupCore, Level3ReallocatesTheLeastWornAgentsEveryTon) {
  GroupConfig c = ec();
  c.t_on_s = 2.0;
  Side s(c);
  const GroupDecision first = s.step(10.0, 10.0);
  EXPECT_EQ(first.active, agents({0, 1}));  // no wear yet: ties go to the lower indices
  EXPECT_EQ(first.reallocations, 1u);
  const GroupDecision before = s.cruise_until(2.0, 10.0);
  EXPECT_EQ(before.active, agents({0, 1}));  // Level 2 at t = 1 s kept the count: no reallocation
  EXPECT_EQ(before.reallocations, 1u);
  EXPECT_EQ(before.decisions, 2u);
  const GroupDecision at_ton = s.step(10.0, 10.0);  // t = 2 s
  EXPECT_EQ(at_ton.active, agents({2, 3}));         // 0 and 1 have worn, the others not
  EXPECT_EQ(at_ton.reallocations, 2u);
  EXPECT_GT(s.core.ledger().wear_m[0], 0.0);
  EXPECT_EQ(s.core.ledger().wear_m[2], 0.0);  // its first metres come with tick 201
}

TEST(GroupCore, Level3ReallocatesWhenTheCountChanges) {
  Side s(ec());
  s.cruise_until(1.5, 10.0);
  EXPECT_EQ(s.in.active, agents({0, 1}));
  // The reference drops to 5 m/s (the body follows): Level 2 wants 3 at its next decision.
  GroupDecision d;
  while (!(d = s.step(5.0, 5.0)).level2_ran) ASSERT_EQ(d.active, agents({0, 1}));
  EXPECT_NEAR(s.in.t, 2.0, 1e-9);
  EXPECT_EQ(d.level2.oracle_n_active, 3);
  EXPECT_EQ(d.n_active, 3);
  EXPECT_EQ(d.active, agents({2, 3, 4}));  // the three least worn
  EXPECT_EQ(d.reallocations, 2u);
}

TEST(GroupCore, Level3ReallocatesWhenAnActiveAgentFails) {
  Side s(ec());
  s.cruise_until(0.5, 10.0);
  ASSERT_EQ(s.in.active, agents({0, 1}));
  s.in.live[0] = 0;  // the plant reports agent 0 lost
  const GroupDecision d = s.step(10.0, 10.0);
  EXPECT_EQ(d.n_active, 2);  // the count is kept
  EXPECT_EQ(d.active[0], 0);
  EXPECT_EQ(d.active, agents({2, 3}));  // the least worn live agents
  EXPECT_EQ(d.reallocations, 2u);
  EXPECT_EQ(d.n_live, kPerSide - 1);
  for (int k = 0; k < 200; ++k) ASSERT_EQ(s.step(10.0, 10.0).active[0], 0) << k;
}

TEST(GroupCore, Level3ReallocatesAtTheThermalLimit) {
  GroupConfig c = ec();
  c.thermal_limit_s = 1.5;
  Side s(c);
  s.cruise_until(1.45, 10.0);
  ASSERT_EQ(s.in.active, agents({0, 1}));
  const GroupDecision d = s.cruise_until(1.6, 10.0);
  EXPECT_EQ(d.active, agents({2, 3}));  // 0 and 1 ran 1.5 s without a pause: cooler ones take over
  EXPECT_EQ(d.reallocations, 2u);
  EXPECT_EQ(s.core.ledger().active_time_s[0], 0.0);  // resting restarts the continuous time
}

TEST(GroupCore, AFreshCoreResumedFromTheLedgerOnTheWireGoesOnAsTheFirstWould) {
  GroupConfig c = ec();
  c.t_on_s = 2.0;
  Side a(c);
  EXPECT_FALSE(a.core.resumed());
  a.cruise_until(2.005, 10.0);  // past the reallocation at t = 2 s
  ASSERT_EQ(a.in.active, agents({2, 3}));

  // The restarted controller: the ledger goes out in the status and comes back in a tick.
  Side b(c);
  b.core.resume(maptr::comm::ledger_of(maptr::comm::to_msg(a.core.ledger()), a.core.ledger().assignment));
  ASSERT_TRUE(b.core.resumed());
  EXPECT_EQ(b.core.ledger().wear_m, a.core.ledger().wear_m);
  EXPECT_EQ(b.core.ledger().active_time_s, a.core.ledger().active_time_s);
  EXPECT_EQ(b.core.ledger().assignment, agents({2, 3}));
  b.in = a.in;
  // It decides as the first goes on deciding, tick by tick, through the next reallocation.
  for (int k = 0; k < 250; ++k) {
    const GroupDecision da = a.step(10.0, 10.0), db = b.step(10.0, 10.0);
    ASSERT_EQ(db.active, da.active) << "tick " << a.in.tick;
    ASSERT_EQ(db.reallocations, da.reallocations) << "tick " << a.in.tick;
  }
  EXPECT_EQ(b.core.ledger().wear_m, a.core.ledger().wear_m);
  EXPECT_EQ(b.core.ledger().last_alloc_t, a.core.ledger().last_alloc_t);
  EXPECT_GT(a.core.ledger().reallocations, 2u);
}

/// Solves at once, and records at which tick (set by the test before each step) the core
/// started and finished each decision and the speed in the problem it was given.
struct RecordingRunner : maptr::control::Level2Runner {
  explicit RecordingRunner(const long long& tick) : tick_(tick), inline_(true) {}
  void start(const maptr::control::Level2Problem& p) override {
    starts.push_back(tick_);
    start_v.push_back(p.v_x);
    inline_.start(p);
  }
  maptr::control::Level2Outcome finish() override {
    finishes.push_back(tick_);
    return inline_.finish();
  }
  const long long& tick_;
  maptr::control::InlineLevel2Runner inline_;
  std::vector<long long> starts, finishes;
  std::vector<double> start_v;
};

/// Speed at tick k of a cruise that wanders around 10 m/s (inside the cruise band).
double wander(long long k) { return 10.0 * (1.0 + 0.03 * std::sin(0.05 * static_cast<double>(k))); }

TEST(GroupCore, DeferredDecisionUsesTheInputsOfItsStartTickAndActsDTicksLater) {
  GroupConfig now_c = ec(), later_c = ec();
  later_c.level2_defer_s = 0.1;  // d = 10 ticks of 10 ms
  Side now(now_c);
  long long tick = 0;
  RecordingRunner rec(tick);
  Side later(later_c, &rec);
  std::vector<GroupDecision> immediate;
  int applied = 0;
  for (; tick < 400; ++tick) {
    const double v = wander(tick);
    immediate.push_back(now.step(v, 10.0));
    const GroupDecision d = later.step(v, 10.0);
    ASSERT_EQ(d.level2_ran, tick >= 10 && tick % 100 == 10) << tick;
    if (!d.level2_ran) continue;
    ++applied;
    const GroupDecision& at_start = immediate[static_cast<std::size_t>(tick - 10)];
    ASSERT_TRUE(at_start.level2_ran) << tick;
    // The same problem (tick k's inputs), solved by a solver with the same history.
    EXPECT_EQ(d.level2.ipopt_n_active, at_start.level2.ipopt_n_active) << tick;
    EXPECT_EQ(d.level2.relaxed, at_start.level2.relaxed) << tick;
    EXPECT_EQ(d.level2.oracle_n_active, at_start.level2.oracle_n_active) << tick;
    EXPECT_NEAR(d.level2.t_s, 0.01 * static_cast<double>(tick - 10), 1e-12);
    EXPECT_EQ(d.n_active, at_start.n_active) << tick;
    // The decision's record says what the side runs from it and how many were live then.
    EXPECT_EQ(d.level2.n_target, d.n_active) << tick;
    EXPECT_EQ(d.level2.n_live, d.n_live) << tick;
  }
  EXPECT_EQ(applied, 4);
  ASSERT_EQ(rec.starts, (std::vector<long long>{0, 100, 200, 300}));
  EXPECT_EQ(rec.finishes, (std::vector<long long>{10, 110, 210, 310}));
  for (std::size_t i = 0; i < rec.starts.size(); ++i) EXPECT_DOUBLE_EQ(rec.start_v[i], wander(rec.starts[i]));
}

TEST(GroupCore, UntilTheFirstDeferredDecisionEveryLiveAgentRuns) {
  GroupConfig c = ec();
  c.level2_defer_s = 0.05;
  Side s(c);
  for (int k = 0; k < 5; ++k) ASSERT_EQ(s.step(10.0, 10.0).n_active, kPerSide) << k;
  const GroupDecision d = s.step(10.0, 10.0);  // tick 5: the decision of tick 0
  ASSERT_TRUE(d.level2_ran);
  EXPECT_EQ(d.n_active, d.level2.oracle_n_active);
  EXPECT_LT(d.n_active, kPerSide);
}

TEST(GroupCore, ADecisionPendingWhenCruiseEndsIsDropped) {
  GroupConfig c = ec();
  c.level2_defer_s = 0.1;
  long long tick = 0;
  RecordingRunner rec(tick);
  Side s(c, &rec);
  ASSERT_FALSE(s.step(10.0, 10.0).level2_ran);  // tick 0: started
  for (tick = 1; tick < 5; ++tick) s.step(10.0, 10.0);
  for (; tick < 30; ++tick) {  // 25 % below the reference from tick 5: out of cruise
    const GroupDecision d = s.step(7.5, 10.0);
    ASSERT_FALSE(d.level2_ran) << tick;
    ASSERT_EQ(d.n_active, kPerSide) << tick;
  }
  EXPECT_EQ(rec.starts, (std::vector<long long>{0}));
  EXPECT_EQ(rec.finishes, (std::vector<long long>{10}));  // collected when due, and not used
  EXPECT_EQ(s.core.ledger().decisions, 0u);
  // Back in cruise: a new decision starts at once and acts 10 ticks later.
  s.step(10.0, 10.0);
  EXPECT_EQ(rec.starts.back(), 30);
}

}  // namespace
