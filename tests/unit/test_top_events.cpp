// `maptr top`'s events from a run's files: a gate names the faults scheduled at its tick, and a
// replay's event list is the run's own record, in simulated-time order, released as the
// replayed ticks reach it.
#include <gtest/gtest.h>

#include "deploy/top/fleet_view.hpp"
#include "deploy/top/run_events.hpp"
#include "deploy/top/view_text.hpp"

namespace {

using namespace maptr;

TEST(TopEvents, AGateNamesTheFaultsScheduledAtItsTick) {
  config::Scenario s;
  s.tick_hz = 100;
  s.faults = {config::FaultSpec::of("L1", "restart", 8.0), config::FaultSpec::of("L1", "kill", 5.0),
              config::FaultSpec::of("R0", "kill", 5.0), config::FaultSpec::of("L2", "fault", 6.0)};
  s.faults.back().mode = "open";
  const auto g = top::gate_faults(s);
  ASSERT_EQ(g.size(), 2u);  // the agent fault has no gate
  EXPECT_EQ(g.at(500), "kill of L1, kill of R0");
  EXPECT_EQ(g.at(800), "restart of L1");
}

TEST(TopEvents, ARunsRecordBecomesItsEventListInTimeOrder) {
  const nlohmann::json summary = {
      {"failures",
       {{{"action", "kill"}, {"target", "L3"}, {"at_s", 4.0}, {"origin", "scheduled"}},
        {{"action", "fault"}, {"target", "R1"}, {"at_s", 2.5}, {"mode", "torque"}, {"value", 0.5}, {"origin", "chaos"}},
        {{"action", "kill"}, {"target", "L5"}, {"at_s", 99.0}, {"skipped", "scheduled after the end of the run"}}}},
      {"membership_events",
       {{{"process", "L3"}, {"kind", "died"}, {"t_s", 4.0}, {"cause", "scheduled"}},
        {{"process", "central"}, {"kind", "paused"}, {"t_s", 3.0}, {"cause", "command"}}}},
      {"plant", {{"agent_faults", {{"diagnoses", {{{"t_s", 2.6}, {"target", "R1"}, {"event", "isolated"}, {"diagnosed", "torque"}}}}}}}}};
  const auto ev = top::recorded_events(summary, 100.0);
  std::vector<std::string> texts;
  for (const auto& e : ev) texts.push_back(e.text);
  EXPECT_EQ(texts, (std::vector<std::string>{"chaos fault torque=0.5 of R1 (tick 250)", "R1 isolated by its group (torque)",
                                             "central paused (command)", "scheduled kill of L3 (tick 400)",
                                             "L3 died (scheduled)"}));
}

msg::PlantTick tick_at(uint64_t k, double t, msg::RunState state) {
  msg::PlantTick p;
  p.tick(k);
  p.t(t);
  p.run_state(state);
  return p;
}

TEST(TopEvents, AReplayedViewReleasesTheRecordAsTheTicksReachIt) {
  top::FleetView v(top::RunInfo{"s", "/tmp/x", 8, 10, 0, 1});
  v.set_recorded_events({{5.0, "L3 died (scheduled)"}, {2.0, "central paused (command)"}});
  v.on_tick(tick_at(300, 3.0, msg::RUN_RUNNING), 0.0);
  ASSERT_EQ(v.events().size(), 1u);
  EXPECT_EQ(v.events()[0].text, "central paused (command)");
  // A membership sample over DDS changes the cells but not the list.
  msg::MembershipEvent e;
  e.name("L3");
  e.node_kind(msg::NODE_AGENT);
  e.side(msg::SIDE_L);
  e.index(3);
  e.kind(msg::MEMBER_DIED);
  v.on_membership(e);
  EXPECT_EQ(v.events().size(), 1u);
  EXPECT_EQ(v.state(0, 3), top::CellState::kDead);
  v.on_tick(tick_at(1000, 10.0, msg::RUN_FINISHED), 1.0);
  ASSERT_EQ(v.events().size(), 3u);
  EXPECT_EQ(v.events()[1].text, "L3 died (scheduled)");
  EXPECT_EQ(v.events()[2].text, "run finished");
}

TEST(TopEvents, APauseIsNotAStart) {
  top::FleetView v(top::RunInfo{"s", "/tmp/x", 8, 10, 0, 0});
  msg::MembershipEvent e;
  e.name("central");
  e.node_kind(msg::NODE_CENTRAL);
  e.kind(msg::MEMBER_PAUSED);
  v.on_membership(e);
  ASSERT_EQ(v.events().size(), 1u);
  EXPECT_EQ(v.events()[0].text, "central paused");
}

}  // namespace

namespace {
TEST(TopEvents, TheScreenKeepsEveryEventAndScrollsBack) {
  top::FleetView v(top::RunInfo{"s", "/tmp/x", 8, 10, 0, 1});
  std::vector<top::ViewEvent> ev;
  for (int i = 0; i < 20; ++i) ev.push_back({static_cast<double>(i), "event " + std::to_string(i)});
  v.set_recorded_events(ev);
  v.on_summary("ok", "finished");  // a finished run: every recorded event is in the list
  ASSERT_EQ(v.events().size(), 20u);
  const auto joined = [](const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
  };
  // A snapshot (no height) shows all 20.
  const std::string all = joined(top::layout(v, 100, 0));
  EXPECT_NE(all.find("event 0\n"), std::string::npos) << all;
  EXPECT_NE(all.find("event 19\n"), std::string::npos) << all;
  // A 24-line screen the latest 4, then scrolled back by 10, then past the first (clamped).
  const std::string latest = joined(top::layout(v, 100, 24));
  EXPECT_NE(latest.find("events 17-20 of 20"), std::string::npos) << latest;
  EXPECT_NE(latest.find("event 19\n"), std::string::npos);
  const std::string back = joined(top::layout(v, 100, 24, 10));
  EXPECT_NE(back.find("events 7-10 of 20"), std::string::npos) << back;
  EXPECT_NE(back.find("event 9\n"), std::string::npos);
  EXPECT_EQ(back.find("event 19\n"), std::string::npos);
  EXPECT_NE(joined(top::layout(v, 100, 24, 999)).find("events 1-4 of 20"), std::string::npos);
}
}  // namespace
