// The properties of `maptr check` on small hand-made histories: each holds on one and breaks on
// another, at the tick where the history breaks it; arguments are parsed with their rules; the
// committed docs/PROPERTIES.md is the table.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "deploy/fleet/run_properties.hpp"

namespace {

namespace props = maptr::deploy::properties;
using maptr::records::TraceRow;

/// A history of 8 agents at 100 Hz: `n` trace rows, one per 10 ms, cruising at 10 rad/s from
/// the start on both sides, all agents live, on the path; a complete recording.
props::History cruising(int n = 100) {
  props::History h;
  h.summary = {{"tick_hz", 100.0},
               {"agents", 8},
               {"sim_time_s", n / 100.0},
               {"failures", nlohmann::json::array()},
               {"membership_events", nlohmann::json::array()},
               {"processes", nlohmann::json::array({{{"name", "plant"}, {"exit_code", 0}, {"signal", 0}}})},
               {"recording", {{"incomplete", nlohmann::json::object()}}},
               {"plant",
                {{"agent_faults", {{"diagnoses", nlohmann::json::array()}}},
                 {"group_wear", {{"L", {{"regressions", 0}}}, {"R", {{"regressions", 0}}}}},
                 {"energy_ledger",
                  {{"drawn_J", 1000.0},
                   {"kinetic_start_J", 0.0},
                   {"kinetic_end_J", 15.0},
                   {"joule_loss_J", 885.0},
                   {"mech_loss_J", 99.5},
                   {"emf_loss_J", 0.5}}}}}};
  for (int k = 0; k < n; ++k) {
    TraceRow r;
    r.tick = k;
    r.t_s = k / 100.0;
    r.ref_L_radps = r.ref_R_radps = 10.0;
    r.phidot_L_radps = r.phidot_R_radps = 10.0;
    r.n_live_L = r.n_live_R = 4;
    h.trace.push_back(r);
  }
  h.recording_file = true;
  return h;
}

props::Verdict check(const std::string& spec, const props::History& h) {
  return props::evaluate(props::parse_spec(spec), h);
}

TEST(RunProperties, EveryPropertyHoldsOnACleanHistory) {
  const auto h = cruising();
  for (const auto& s : props::all_specs()) {
    const auto v = props::evaluate(s, h);
    EXPECT_TRUE(v.holds) << v.property << ": " << v.reason;
    EXPECT_EQ(v.tick, -1);
  }
}

TEST(RunProperties, SpeedBandBreaksAtTheFirstRowOutsideAndExcusesARecoveryWindow) {
  auto h = cruising();
  h.trace[40].phidot_L_radps = h.trace[40].phidot_R_radps = 8.0;  // 20 % slow at tick 40
  auto v = check("speed_band:10", h);
  EXPECT_FALSE(v.holds);
  EXPECT_EQ(v.tick, 40);
  EXPECT_TRUE(check("speed_band:25", h).holds);
  // A kill at 0.35 s that the speed recovered from at 0.45 s excuses tick 40.
  h.summary["failures"].push_back({{"action", "kill"}, {"target", "L1"}, {"at_s", 0.35}, {"recovered_s", 0.45}});
  EXPECT_TRUE(check("speed_band:10", h).holds);
  // One that never recovered excuses the rest of the run.
  h.summary["failures"][0].erase("recovered_s");
  h.trace[80].phidot_L_radps = 0;
  EXPECT_TRUE(check("speed_band:10", h).holds);
}

TEST(RunProperties, SpeedBandStartsWhenTheSpeedFirstReachesTheReference) {
  auto h = cruising();
  for (int k = 0; k < 30; ++k) h.trace[k].phidot_L_radps = h.trace[k].phidot_R_radps = k / 3.0;  // a ramp
  EXPECT_TRUE(check("speed_band:1", h).holds);
  h.trace[60].phidot_L_radps = 12.0;  // 10 % fast on the mean after it was reached
  const auto v = check("speed_band:5", h);
  EXPECT_FALSE(v.holds);
  EXPECT_EQ(v.tick, 60);
  for (auto& r : h.trace) r.phidot_L_radps = r.phidot_R_radps = 5.0;  // never reaches it
  EXPECT_FALSE(check("speed_band:5", h).holds);
}

TEST(RunProperties, PathTrackedAgainstTheScenariosToleranceOrTheArgument) {
  auto h = cruising();
  h.path_tolerance_m = 0.3;
  h.trace[70].cross_track_m = -0.31;
  auto v = check("path_tracked", h);
  EXPECT_FALSE(v.holds);
  EXPECT_EQ(v.tick, 70);
  EXPECT_NE(v.reason.find("0.310 m"), std::string::npos) << v.reason;
  EXPECT_TRUE(check("path_tracked:0.5", h).holds);
}

TEST(RunProperties, FaultsDetectedWithinTheLimitAndNeverDetectedBreaks) {
  auto h = cruising();
  h.summary["failures"].push_back(
      {{"action", "fault"}, {"target", "L3"}, {"mode", "open"}, {"at_s", 0.2}, {"detected_s", 0.5}});
  EXPECT_TRUE(check("faults_detected:0.3", h).holds);
  auto v = check("faults_detected:0.2", h);
  EXPECT_FALSE(v.holds);
  EXPECT_EQ(v.tick, 40);  // 0.2 s act + 0.2 s limit
  h.summary["failures"][0]["detected_s"] = nullptr;
  v = check("faults_detected", h);
  EXPECT_FALSE(v.holds);
  EXPECT_NE(v.reason.find("never detected"), std::string::npos) << v.reason;
  // The end of a fault is no fault to detect, even when the summary says when it was seen.
  h.summary["failures"] = nlohmann::json::array(
      {{{"action", "restart"}, {"target", "L3"}, {"at_s", 0.5}},
       {{"action", "resume"}, {"target", "L2"}, {"at_s", 0.5}, {"detected_s", 0.9}}});
  EXPECT_TRUE(check("faults_detected", h).holds);
}

TEST(RunProperties, AHealthyAgentIsolatedIsAFalseDetection) {
  auto h = cruising();
  h.summary["plant"]["agent_faults"]["diagnoses"].push_back(
      {{"target", "R2"}, {"event", "isolated"}, {"diagnosed", "open"}, {"false_detection", false}, {"t_s", 0.3}});
  EXPECT_TRUE(check("no_false_detection", h).holds);
  h.summary["plant"]["agent_faults"]["diagnoses"].push_back(
      {{"target", "R1"}, {"event", "isolated"}, {"diagnosed", "short"}, {"false_detection", true}, {"t_s", 0.55}});
  const auto v = check("no_false_detection", h);
  EXPECT_FALSE(v.holds);
  EXPECT_EQ(v.tick, 55);
  EXPECT_NE(v.reason.find("R1"), std::string::npos);
}

TEST(RunProperties, ARecordingMissingOrShortBreaksUnlessNoneWasAsked) {
  auto h = cruising();
  h.summary["recording"]["incomplete"]["maptr/tick"] = {{"recorded", 90}, {"taken_by_plant", 100}};
  auto v = check("recording_complete", h);
  EXPECT_FALSE(v.holds);
  EXPECT_NE(v.reason.find("maptr/tick 90 of 100"), std::string::npos) << v.reason;
  h = cruising();
  h.recording_file = false;
  EXPECT_FALSE(check("recording_complete", h).holds);
  h.record = "none";
  EXPECT_TRUE(check("recording_complete", h).holds);
}

TEST(RunProperties, ALedgerThatWentBackwardsBreaksAtItsFirstRegression) {
  auto h = cruising();
  h.summary["plant"]["group_wear"]["R"] = {{"regressions", 2}, {"first_regression_s", 0.61}, {"largest_drop_m", 0.5}};
  const auto v = check("ledger_monotone", h);
  EXPECT_FALSE(v.holds);
  EXPECT_EQ(v.tick, 61);
  EXPECT_NE(v.reason.find("group-R"), std::string::npos);
}

TEST(RunProperties, EnergyBalanceHoldsWithinItsToleranceAndBreaksAtTheEndOutsideIt) {
  auto h = cruising();
  auto v = check("energy_balance", h);
  EXPECT_TRUE(v.holds) << v.reason;
  // 2 J of 1000 drawn went nowhere: 0.2 % apart.
  h.summary["plant"]["energy_ledger"]["mech_loss_J"] = 97.5;
  v = check("energy_balance", h);
  EXPECT_FALSE(v.holds);
  EXPECT_EQ(v.tick, 100);  // judged at the end of the run
  EXPECT_NE(v.reason.find("0.2000 % apart"), std::string::npos) << v.reason;
  EXPECT_TRUE(check("energy_balance:0.5", h).holds);
  // Energy that comes from nowhere breaks it too.
  h.summary["plant"]["energy_ledger"]["mech_loss_J"] = 101.5;
  EXPECT_FALSE(check("energy_balance", h).holds);
  // A run whose plant left no ledger cannot be said to balance.
  h.summary["plant"].erase("energy_ledger");
  v = check("energy_balance", h);
  EXPECT_FALSE(v.holds);
  EXPECT_NE(v.reason.find("no energy ledger"), std::string::npos) << v.reason;
}

TEST(RunProperties, ADeathNoFaultExplainsIsUnexpected) {
  auto h = cruising();
  h.summary["membership_events"].push_back({{"kind", "died"}, {"process", "L1"}, {"cause", "scheduled"}, {"t_s", 0.1}});
  EXPECT_TRUE(check("no_unexpected_exit", h).holds);
  h.summary["membership_events"].push_back({{"kind", "died"}, {"process", "R0"}, {"cause", "lease"}, {"t_s", 0.4}});
  auto v = check("no_unexpected_exit", h);
  EXPECT_FALSE(v.holds);
  EXPECT_EQ(v.tick, 40);
  // A host killed before it explains its processes' lost leases.
  h.summary["failures"].push_back({{"action", "kill-host"}, {"target", "h2"}, {"at_s", 0.3}});
  EXPECT_TRUE(check("no_unexpected_exit", h).holds);
  // A process that exited with an error code is unexpected whatever the faults.
  h.summary["processes"].push_back({{"name", "group-L"}, {"exit_code", 3}, {"signal", 0}});
  v = check("no_unexpected_exit", h);
  EXPECT_FALSE(v.holds);
  EXPECT_NE(v.reason.find("group-L exited with code 3"), std::string::npos) << v.reason;
}

TEST(RunProperties, MaxDeadPerSideCountsEachSideAndDefaultsToAllButOne) {
  auto h = cruising();
  for (int k = 30; k < 60; ++k) h.trace[k].n_live_L = 2;
  for (int k = 50; k < 60; ++k) h.trace[k].n_live_L = 1;
  EXPECT_TRUE(check("max_dead_per_side", h).holds);  // 3 of 4 dead: one is left
  EXPECT_TRUE(check("max_dead_per_side:3", h).holds);
  auto v = check("max_dead_per_side:2", h);
  EXPECT_FALSE(v.holds);
  EXPECT_EQ(v.tick, 50);
  v = check("max_dead_per_side:1", h);
  EXPECT_EQ(v.tick, 30);
  h.trace[90].n_live_R = 0;
  EXPECT_EQ(check("max_dead_per_side", h).tick, 90);
}

TEST(RunProperties, SpecsAreParsedWithTheirRules) {
  EXPECT_EQ(props::parse_spec("speed_band").arg, 10.0);
  EXPECT_EQ(props::parse_spec("speed_band:2.5").arg, 2.5);
  EXPECT_EQ(props::parse_spec("speed_band:2.5").text(), "speed_band:2.5");
  EXPECT_FALSE(props::parse_spec("path_tracked").arg.has_value());
  for (const char* bad : {"nope", "speed_band:", "speed_band:x", "speed_band:-1", "speed_band:nan",
                          "ledger_monotone:3", "max_dead_per_side:2x"}) {
    try {
      props::parse_spec(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

TEST(RunProperties, TheCommittedReferenceIsTheTable) {
  std::ifstream f(std::string(MAPTR_SOURCE_DIR) + "/docs/PROPERTIES.md");
  std::stringstream ss;
  ss << f.rdbuf();
  EXPECT_EQ(ss.str(), props::reference(true))
      << "docs/PROPERTIES.md differs from the table: build/bin/maptr check --list --markdown > docs/PROPERTIES.md";
}

}  // namespace
