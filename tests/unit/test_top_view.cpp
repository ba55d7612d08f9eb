// The fleet view of `maptr top` (deploy/top/fleet_view, view_text): samples in, what the screen
// shows out; every arrival time is given explicitly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "deploy/top/fleet_view.hpp"
#include "deploy/top/view_text.hpp"

using namespace maptr::top;
namespace msg = maptr::msg;

namespace {

RunInfo info(int agents) { return {"default", "runs/x", agents, 60.0, 200}; }

msg::PlantTick tick(long long k, double dt, int per_side, msg::RunState st = msg::RUN_RUNNING) {
  msg::PlantTick t;
  t.tick(static_cast<uint64_t>(k));
  t.t(static_cast<double>(k) * dt);
  t.run_state(st);
  for (auto& s : t.sides()) {
    s.live(std::vector<uint8_t>(static_cast<std::size_t>(per_side), 1));
    s.active(std::vector<uint8_t>(static_cast<std::size_t>(per_side), 0));
  }
  return t;
}

msg::AgentReply reply(long long k, msg::Side side, int index, msg::AgentState st) {
  msg::AgentReply r;
  r.tick(static_cast<uint64_t>(k));
  r.side(side);
  r.index(static_cast<uint16_t>(index));
  r.state(st);
  r.voltage_V(12.5);
  r.current_A(1.25);
  return r;
}

msg::MembershipEvent member(const std::string& name, msg::Side side, int index, msg::MemberEvent kind) {
  msg::MembershipEvent e;
  e.name(name);
  e.node_kind(msg::NODE_AGENT);
  e.side(side);
  e.index(static_cast<uint16_t>(index));
  e.kind(kind);
  return e;
}

/// Every agent of `v` replies to tick k at `at_s` with `st`.
void all_reply(FleetView& v, long long k, double at_s, msg::AgentState st = msg::AGENT_ACTIVE) {
  for (int s = 0; s < 2; ++s)
    for (std::size_t i = 0; i < v.side(s).agents.size(); ++i)
      v.on_reply(reply(k, static_cast<msg::Side>(s), static_cast<int>(i), st), at_s);
}

bool has_line(const std::vector<std::string>& lines, const std::string& part) {
  return std::any_of(lines.begin(), lines.end(),
                     [&](const std::string& l) { return l.find(part) != std::string::npos; });
}

}  // namespace

TEST(TopView, TickMedianAndP99FromArrivalIntervals) {
  FleetView v(info(4));
  // Intervals of 1, 2, ..., 101 ms: median 51 ms; p99 at rank 0.99 * 100 = 99 -> 100 ms.
  double at = 0.0;
  v.on_tick(tick(0, 0.01, 2), at);
  for (int k = 1; k <= 101; ++k) v.on_tick(tick(k, 0.01, 2), at += k * 1e-3);
  const TickStats s = v.tick_stats();
  EXPECT_EQ(s.n, 101u);
  EXPECT_NEAR(s.median_ms, 51.0, 1e-9);
  EXPECT_NEAR(s.p99_ms, 100.0, 1e-9);
}

TEST(TopView, RealTimeFactorIsSimulatedOverWallTimeAndGapsAreNoInterval) {
  FleetView v(info(4));
  for (int k = 0; k <= 100; ++k) v.on_tick(tick(k, 0.01, 2), 10.0 + 0.002 * k);  // 10 ms each 2 ms
  EXPECT_NEAR(v.real_time_factor(), 5.0, 1e-9);
  v.on_tick(tick(110, 0.01, 2), 10.0 + 0.002 * 100 + 0.5);  // ticks 101..109 not seen
  const TickStats s = v.tick_stats();
  EXPECT_EQ(s.n, 100u);  // no interval across the gap
  EXPECT_NEAR(s.p99_ms, 2.0, 1e-9);
  EXPECT_NEAR(v.t_s(), 1.1, 1e-12);
}

TEST(TopView, AgentStatesFromRepliesLauncherAndPlant) {
  FleetView v(info(4));
  EXPECT_EQ(v.state(0, 0), CellState::kUnknown);
  v.on_tick(tick(1, 0.01, 2), 1.0);
  v.on_reply(reply(1, msg::SIDE_L, 0, msg::AGENT_ACTIVE), 1.0);
  v.on_reply(reply(1, msg::SIDE_L, 1, msg::AGENT_HOLDING), 1.0);
  v.on_reply(reply(1, msg::SIDE_R, 0, msg::AGENT_COASTING), 1.0);
  v.on_reply(reply(1, msg::SIDE_R, 1, msg::AGENT_STOPPING), 1.0);
  v.observe(1.1);
  EXPECT_EQ(v.state(0, 0), CellState::kActive);
  EXPECT_EQ(v.state(0, 1), CellState::kHolding);
  EXPECT_EQ(v.state(1, 0), CellState::kCoasting);
  EXPECT_EQ(v.state(1, 1), CellState::kStopping);
  EXPECT_DOUBLE_EQ(v.side(0).agents[0].voltage_V, 12.5);
  EXPECT_DOUBLE_EQ(v.side(0).agents[0].current_A, 1.25);

  v.on_membership(member("L1", msg::SIDE_L, 1, msg::MEMBER_DIED));
  EXPECT_EQ(v.state(0, 1), CellState::kDead);
  EXPECT_EQ(v.live_agents(), 3);
  auto t = tick(2, 0.01, 2);
  t.sides()[0].live()[1] = 0;  // the plant drops it
  v.on_tick(t, 1.01);
  v.on_membership(member("L1", msg::SIDE_L, 1, msg::MEMBER_STARTED));
  EXPECT_EQ(v.state(0, 1), CellState::kRejoining);
  v.on_tick(t = tick(3, 0.01, 2), 1.02);  // live again in the plant's mask
  v.on_reply(reply(3, msg::SIDE_L, 1, msg::AGENT_IDLE), 1.02);
  EXPECT_EQ(v.state(0, 1), CellState::kIdle);
  EXPECT_EQ(v.live_agents(), 4);

  // R1 stops answering while the others go on: paused once its last reply is kPausedAfter_s old.
  v.observe(1.02 + kPausedAfter_s + 0.01);
  EXPECT_EQ(v.state(1, 1), CellState::kPaused);
  ASSERT_EQ(v.events().size(), 2u);
  EXPECT_EQ(v.events()[0].text, "L1 died");
  EXPECT_NEAR(v.events()[1].t_s, 0.02, 1e-12);
}

TEST(TopView, GroupStatusSpeedAndFinalStatus) {
  FleetView v(info(4));
  auto t = tick(100, 0.01, 2);
  t.v_x(0.9);
  t.sides()[1].battery_V(22.5);
  t.sides()[1].discharge_mAh(3.5);
  v.on_tick(t, 0.0);
  msg::CentralCommand c;
  c.v_x_ref(1.0);
  v.on_central(c);
  EXPECT_NEAR(v.speed_error_pct(), -10.0, 1e-9);

  msg::GroupStatus g;
  g.tick(100);
  g.side(msg::SIDE_R);
  g.n_active(1);
  g.level2_status(msg::L2_INFEASIBLE);
  g.level2_relaxed(1.4);
  g.solve_time_ms(4.5);
  g.ledger().reallocations(3);
  g.ledger().wear_m({12.0, 7.0});
  g.ledger().active_time_s(std::vector<double>(g.ledger().wear_m().size(), 0.0));
  v.on_group(g);
  g.tick(101);
  g.ledger().reallocations(4);
  v.on_group(g);
  EXPECT_EQ(v.side(1).level2.status, maptr::control::kL2Infeasible);
  EXPECT_DOUBLE_EQ(v.side(1).level2.relaxed, 1.4);
  EXPECT_DOUBLE_EQ(v.side(1).level2.solve_ms, 4.5);
  EXPECT_DOUBLE_EQ(v.side(1).agents[0].wear_m, 12.0);
  EXPECT_FALSE(v.group_silent(1));
  EXPECT_TRUE(v.group_silent(0));
  EXPECT_EQ(v.side(1).reallocations, 4u);
  msg::FaultGate gate;
  gate.tick(500);
  gate.t(5.0);
  v.on_gate(gate);
  v.on_membership(member("R1", msg::SIDE_R, 1, msg::MEMBER_DIED), true);
  ASSERT_EQ(v.events().size(), 2u);
  EXPECT_DOUBLE_EQ(v.events()[0].t_s, 5.0);    // the gate's own time
  EXPECT_TRUE(std::isnan(v.events()[1].t_s));  // history: written before the watcher joined

  const auto lines = layout(v, 80, 24);
  EXPECT_TRUE(has_line(lines, "22.50 V     3.500 mAh")) << lines[4] << "\n" << lines[5];
  EXPECT_TRUE(has_line(lines, "infeasible")) << lines[5];
  EXPECT_TRUE(has_line(lines, "4 realloc")) << lines[5];
  EXPECT_TRUE(has_line(lines, "t     5.00 s    scheduled fault (tick 500)"));
  EXPECT_TRUE(has_line(lines, "before joining R1 died"));
  v.on_tick(tick(101, 0.01, 2, msg::RUN_FINISHED), 0.01);
  EXPECT_EQ(v.phase(), Phase::kFinished);
  v.on_summary("ok", "duration reached");
  EXPECT_EQ(layout(v, 80, 24).back().rfind("final status: ok (duration reached) at t 1.01 s", 0), 0u)
      << layout(v, 80, 24).back();
}

TEST(TopView, SixteenAgentsGetOneCellEachIn80x24) {
  FleetView v(info(16));
  v.on_tick(tick(1, 0.01, 8), 0.0);
  all_reply(v, 1, 0.0);
  v.on_membership(member("L3", msg::SIDE_L, 3, msg::MEMBER_DIED));
  v.observe(0.1);
  const auto lines = layout(v, 80, 24);
  EXPECT_LE(lines.size(), 24u);
  for (const auto& l : lines) EXPECT_LE(l.size(), 80u) << l;
  EXPECT_TRUE(has_line(lines, "L3   dead")) << lines[8];
  EXPECT_TRUE(has_line(lines, "R7   active")) << lines[13];
  EXPECT_TRUE(has_line(lines, "live 15/16"));
  EXPECT_TRUE(has_line(lines, "L3 died"));
}

TEST(TopView, HundredTwentyEightAgentsAreSummarisedPerSideIn80x24) {
  FleetView v(info(128));
  v.on_tick(tick(1, 0.01, 64), 0.0);
  all_reply(v, 1, 0.0, msg::AGENT_IDLE);
  v.on_reply(reply(1, msg::SIDE_R, 5, msg::AGENT_ACTIVE), 0.0);
  v.on_membership(member("L63", msg::SIDE_L, 63, msg::MEMBER_DIED));
  v.observe(0.1);
  const auto lines = layout(v, 80, 24);
  EXPECT_LE(lines.size(), 24u);
  for (const auto& l : lines) EXPECT_LE(l.size(), 80u) << l;
  EXPECT_TRUE(has_line(lines, "L  " + std::string(63, '.') + "X"));
  EXPECT_TRUE(has_line(lines,
                       "R  ....."
                       "A" +
                           std::string(58, '.')));
  EXPECT_TRUE(has_line(lines, "L: 63 idle 1 dead"));
  EXPECT_TRUE(has_line(lines, "R: 1 active 63 idle"));
  EXPECT_EQ(lines.back(), legend());
  // The same fleet in a taller terminal gets a cell per agent; unlimited height (--once) too.
  EXPECT_TRUE(has_line(layout(v, 80, 0), "L63  dead"));
  EXPECT_TRUE(has_line(layout(v, 160, 80), "L63  dead"));
}

TEST(TopView, TooSmallATerminalSaysSo) {
  FleetView v(info(16));
  const auto lines = layout(v, 30, 10);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("30x10"), std::string::npos);
}

TEST(TopView, AnAgentItsGroupIsolatedIsShownFaultyNotDead) {
  FleetView v(info(4));
  v.on_tick(tick(1, 0.01, 2), 1.0);
  all_reply(v, 1, 1.0);
  msg::GroupStatus g;
  g.tick(1);
  g.side(msg::SIDE_L);
  g.ledger().wear_m({0.0, 0.0});
  g.ledger().active_time_s(std::vector<double>(g.ledger().wear_m().size(), 0.0));
  g.faulty({0, static_cast<uint8_t>(msg::DIAG_SHORT)});
  v.on_group(g);
  EXPECT_EQ(v.state(0, 1), CellState::kFaulty);
  EXPECT_EQ(state_letter(CellState::kFaulty), 'F');
  EXPECT_EQ(v.state(0, 0), CellState::kActive);
  EXPECT_EQ(v.live_agents(), 4);  // alive: it answers, it only does not drive
  ASSERT_FALSE(v.events().empty());
  EXPECT_EQ(v.events().back().text, "L1 isolated by its group (short)");
  EXPECT_TRUE(has_line(layout(v, 80, 24), "faulty")) << "the screen says so";
  g.tick(2);
  g.faulty({0, 0});
  v.on_group(g);
  EXPECT_EQ(v.state(0, 1), CellState::kActive);
  EXPECT_EQ(v.events().back().text, "L1 let back by its group");
}
