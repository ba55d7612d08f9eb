// The run's outcome (plant/run_outcome.hpp): the run status rules, the end reason, the tick-timing
// statistics and the keys of plant.json.
#include <gtest/gtest.h>

#include <set>

#include "plant/run_outcome.hpp"

namespace {

using namespace maptr;
using plant::run_status;
using plant::RunEnd;

RunEnd healthy() {
  RunEnd e;
  e.live_agents[0] = e.live_agents[1] = 8;
  e.reached_reference = true;
  e.ref_speed_mps = 1.0;
  e.speed_mps = 0.97;
  return e;
}

TEST(PlantReport, StatusOkWithinTheBand) { EXPECT_EQ(run_status(healthy(), 5.0), "ok"); }

TEST(PlantReport, StopSignalAborts) {
  RunEnd e = healthy();
  e.stopped = true;
  e.live_agents[0] = 0;  // aborted wins over degraded
  EXPECT_EQ(run_status(e, 5.0), "aborted: stop signal");
  EXPECT_TRUE(plant::aborted(run_status(e, 5.0)));
  EXPECT_FALSE(plant::aborted(run_status(healthy(), 5.0)));
}

TEST(PlantReport, SideWithoutLiveAgentDegrades) {
  RunEnd e = healthy();
  e.live_agents[1] = 0;
  EXPECT_EQ(run_status(e, 5.0), "degraded: side R has no live agent; the robot stopped");
  e.live_agents[0] = 0;
  EXPECT_EQ(run_status(e, 5.0), "degraded: side L has no live agent; the robot stopped");
}

TEST(PlantReport, AControllerDeadOrPausedAtTheEndDegrades) {
  RunEnd e = healthy();
  e.silent_controllers = {"central"};
  EXPECT_EQ(run_status(e, 5.0), "degraded: central dead or paused at the end; its agents ran on their own safe behaviour");
  e.silent_controllers = {"group-L", "central"};
  EXPECT_EQ(run_status(e, 5.0),
            "degraded: group-L, central dead or paused at the end; their agents ran on their own safe behaviour");
  e.live_agents[0] = 0;  // a side without agents says more
  EXPECT_EQ(run_status(e, 5.0), "degraded: side L has no live agent; the robot stopped");
}

TEST(PlantReport, EndingOffTheReferenceSpeedDegrades) {
  RunEnd e = healthy();
  e.speed_mps = 0.94;  // 6 % below
  const std::string s = run_status(e, 5.0);
  EXPECT_EQ(s.rfind("degraded: the robot ended 6.0", 0), 0u) << s;
  EXPECT_NE(s.find("% off its reference speed"), std::string::npos) << s;
  e.speed_mps = 1.06;  // 6 % above
  EXPECT_EQ(run_status(e, 5.0).rfind("degraded", 0), 0u);
  EXPECT_EQ(run_status(e, 7.0), "ok");  // a wider band
}

TEST(PlantReport, SpeedNotJudgedWhenNeverReachedOrLost) {
  RunEnd e = healthy();
  e.speed_mps = 0.5;
  e.reached_reference = false;  // a run too short to reach its speed
  EXPECT_EQ(run_status(e, 5.0), "ok");
  e.reached_reference = true;
  e.speed_lost = true;  // ended early: the end reason says why
  EXPECT_EQ(run_status(e, 5.0), "ok");
  e.speed_lost = false;
  e.ref_speed_mps = 0.0;  // standing still
  EXPECT_EQ(run_status(e, 5.0), "ok");
}

TEST(PlantReport, EndReason) {
  EXPECT_EQ(plant::end_reason(false, 20.0, 5.0, 12.0), "duration reached");
  EXPECT_EQ(plant::end_reason(true, 20.0, 5.0, 12.5),
            "the speed stayed more than 20.000000% below its reference for 5 s at t=12.500000 s");
}

TEST(PlantReport, TimingQuantiles) {
  plant::TickTiming t;
  for (int i = 100; i >= 1; --i)
    t.add(float(i), i % 2 ? float(i) : -1.0f, 2.0f * i, 1.0f, 3.0f * i, plant::TickNote{});
  const auto j = t.json();
  EXPECT_EQ(j["publish"]["median"].get<float>(), 50.0f);  // nearest rank below: v[49]
  EXPECT_EQ(j["publish"]["p90"].get<float>(), 90.0f);
  EXPECT_EQ(j["publish"]["p99"].get<float>(), 99.0f);
  EXPECT_EQ(j["publish"]["max"].get<float>(), 100.0f);
  EXPECT_DOUBLE_EQ(j["publish"]["mean"].get<double>(), 50.5);
  EXPECT_EQ(j["publish"]["n"].get<std::size_t>(), 100u);
  EXPECT_EQ(j["first_reply"]["n"].get<std::size_t>(), 50u);  // ticks without a reply are left out
  EXPECT_EQ(j["barrier"]["median"].get<float>(), 100.0f);
  EXPECT_EQ(j["tick"]["p99"].get<float>(), 297.0f);
  EXPECT_TRUE(j["period"].empty());  // no period measured
  EXPECT_TRUE(plant::TickTiming().json()["tick"].empty());
  EXPECT_TRUE(plant::TickTiming().json()["slowest_1pct"].empty());
}

TEST(PlantReport, TheSlowestTicksAreToldApartByWhatTheyHadInCommon) {
  plant::TickTiming t;
  // 200 ticks: the last answer is an agent's, one in ten wrote a trace row; the two slowest
  // (1 % of 200) were answered last by a group solving Level 2, and traced.
  for (int i = 0; i < 200; ++i) {
    plant::TickNote n;
    n.last = plant::TickNote::kAgent;
    n.traced = i % 10 == 0;
    float tick_us = 100.0f + static_cast<float>(i % 7);
    if (i == 50 || i == 150) {
      n.last = plant::TickNote::kGroup;
      n.level2_solving = true;
      tick_us = 5000.0f + static_cast<float>(i);
    }
    t.add(1.0f, 1.0f, tick_us - 2.0f, 1.0f, tick_us, n);
    t.add_period(tick_us + 10.0f);
  }
  const auto s = t.json()["slowest_1pct"];
  EXPECT_EQ(s["n"].get<double>(), 2.0);
  EXPECT_EQ(s["threshold_us"].get<float>(), 5050.0f);  // the faster of the two
  EXPECT_DOUBLE_EQ(s["slowest"]["last_group_pct"].get<double>(), 100.0);
  EXPECT_DOUBLE_EQ(s["slowest"]["level2_solving_pct"].get<double>(), 100.0);
  EXPECT_DOUBLE_EQ(s["slowest"]["traced_pct"].get<double>(), 100.0);  // ticks 50 and 150
  EXPECT_DOUBLE_EQ(s["all"]["last_agent_pct"].get<double>(), 99.0);
  EXPECT_DOUBLE_EQ(s["all"]["traced_pct"].get<double>(), 10.0);
  const auto period = t.json()["period"];
  EXPECT_EQ(period["n"].get<std::size_t>(), 200u);
  EXPECT_GT(period["mean"].get<double>(), period["median"].get<float>());  // the tail pulls the mean up
  EXPECT_EQ(period["max"].get<float>(), 5160.0f);
}

TEST(PlantReport, PlantJsonKeysAndMembershipEvents) {
  plant_core::PlantCoreConfig c;
  plant_core::PlantCore core(c);
  plant::ReportInputs in;
  in.status = "ok";
  in.end_reason = "duration reached";
  in.tick_hz = 100.0;
  in.live_agents[0] = 8;
  in.live_agents[1] = 7;
  in.rejected_samples = 3;
  in.late_samples = 2;
  in.rejected_by_kind = {{"forged", 2}, {"conflicting", 1}, {"late", 2}};
  in.loop_scheduling = "SCHED_FIFO 1 on CPU 1";
  const std::vector<plant::MembershipRecord> events = {{"L1", "died (launcher)", 5.0, 123.5}};
  const auto j = maptr::records::to_json(plant::plant_results(core, in, events));
  std::set<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.insert(k);
  EXPECT_EQ(keys, (std::set<std::string>{"status",
                                         "answers_taken",
                                         "sim_time_s",
                                         "ticks",
                                         "tick_hz",
                                         "loop_wall_s",
                                         "distance_m",
                                         "energy_J",
                                         "energy_side_J",
                                         "energy_ledger",
                                         "mean_active_agents",
                                         "active_agents",
                                         "live_agents",
                                         "battery_discharge_mAh",
                                         "battery_state_mAh",
                                         "agent_active_s",
                                         "end_reason",
                                         "battery_V",
                                         "pose",
                                         "final_speed_mps",
                                         "max_speed_error_pct",
                                         "rms_speed_error_pct",
                                         "rejected_samples",
                                         "rejected_by_process",
                                         "rejected_by_kind",
                                         "late_samples",
                                         "missed_deadlines", "loop_scheduling", "tick_repairs",
                                         "tick_timing_us",
                                         "declared_dead_by_deadline",
                                         "membership_events",
                                         "group_wear", "path", "agent_faults"}));
  EXPECT_EQ(j["live_agents"]["R"], 7);
  EXPECT_EQ(j["rejected_samples"], 3);
  EXPECT_EQ(j["late_samples"], 2);
  EXPECT_EQ(j["rejected_by_kind"]["forged"], 2);
  EXPECT_EQ(j["rejected_by_kind"]["conflicting"], 1);
  EXPECT_EQ(j["loop_scheduling"], "SCHED_FIFO 1 on CPU 1");
  EXPECT_EQ(j["agent_active_s"]["L"].size(), 8u);
  EXPECT_EQ(
      j["membership_events"],
      nlohmann::json::parse(R"js([{"name":"L1","event":"died (launcher)","t_s":5.0,"wall_ms":123.5}])js"));
}

}  // namespace
