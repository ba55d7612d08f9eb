// Agents that fail while their process runs on (ctest label `faults`): real fleets of 16 agents
// on the default scenario (the warehouse loop, 30 kg), one fault on L3 at t = 20 s in each mode:
// detected by its group within 1 s of simulated time, diagnosed right where the drive's
// measurements tell the modes apart, isolated, and the speed back within 2 %.
#include <gtest/gtest.h>

#include <string>

#include "tests/integration/fleet_runner.hpp"

using namespace maptr::testing;

namespace {

std::string default_scenario() { return std::string(MAPTR_SOURCE_DIR) + "/deploy/scenarios/default.yaml"; }

/// The summary's record of the agents' own fault on `target`.
const nlohmann::json* agent_fault(const nlohmann::json& s, const std::string& target) {
  for (const auto& f : s["failures"])
    if (f.value("action", "") == "fault" && f.value("target", "") == target) return &f;
  return nullptr;
}

}  // namespace

TEST(AgentFaults, EachModeOnL3IsDetectedWithinASecondIsolatedAndTheSpeedRecovers) {
  struct Case {
    const char* fault;
    const char* mode;
    const char* diagnosed;  ///< nullptr: any (the drive's measurements cannot always tell)
  } cases[] = {
      {"L3:open@20", "open", "open"},         {"L3:short@20", "short", "short"},
      {"L3:torque=0.5@20", "torque", nullptr}, {"L3:resistance=3@20", "resistance", nullptr},
      {"L3:stuck=12@20", "stuck", "stuck"},   {"L3:sensor=5@20", "sensor", "sensor"},
      {"L3:erratic=2@20", "erratic", nullptr}, {"L3:liar@20", "liar", nullptr},
  };
  for (const auto& c : cases) {
    TempDir tmp;
    const std::string out = tmp.path() + "/run";
    auto r = run_cli(run_args(out, {default_scenario(), "--duration", "30", "--fault", c.fault}), out, 300);
    ASSERT_EQ(r.exit_code, 0) << c.fault << "\n" << r.output;
    const auto& s = r.summary;
    EXPECT_EQ(s["status"], "ok") << c.fault;
    const nlohmann::json* f = agent_fault(s, "L3");
    ASSERT_NE(f, nullptr) << c.fault << s["failures"].dump();
    EXPECT_EQ((*f)["mode"], c.mode);
    EXPECT_DOUBLE_EQ((*f)["injected_s"].get<double>(), 20.0);
    ASSERT_FALSE((*f)["detected_s"].is_null()) << c.fault << f->dump();
    EXPECT_LE((*f)["detected_s"].get<double>() - 20.0, 1.0) << c.fault;
    ASSERT_FALSE((*f)["isolated_s"].is_null()) << c.fault;
    if (c.diagnosed) EXPECT_EQ((*f)["diagnosed_mode"], c.diagnosed) << c.fault;
    ASSERT_FALSE((*f)["recovered_s"].is_null()) << c.fault << f->dump();
    EXPECT_LT((*f)["max_speed_error_pct"].get<double>(), 2.0) << c.fault;
    EXPECT_EQ(s["plant"]["agent_faults"]["false_detections"], 0) << c.fault;
    // The group announced it (the plant disconnected it from then on), and nothing else.
    const auto& d = s["plant"]["agent_faults"]["diagnoses"];
    ASSERT_GE(d.size(), 1u) << c.fault;
    EXPECT_EQ(d[0]["target"], "L3");
    EXPECT_EQ(d[0]["event"], "isolated");
  }
}

TEST(AgentFaults, OneModeGivesTheSameTraceInTwoRuns) {
  std::string sha[2];
  for (int i = 0; i < 2; ++i) {
    TempDir tmp;
    const std::string out = tmp.path() + "/run";
    auto r = run_cli(run_args(out, {default_scenario(), "--duration", "25", "--fault", "L3:erratic=2@20"}), out, 300);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    sha[i] = r.summary["trace_sha256"];
    ASSERT_FALSE(agent_fault(r.summary, "L3")->at("detected_s").is_null());
  }
  EXPECT_EQ(sha[0], sha[1]);
}

TEST(AgentFaults, WeakMagnetsOnFourAgentsAndTwoLiarsAreIsolatedAndThePathIsKept) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  std::vector<std::string> args = {default_scenario()};
  for (const char* f : {"L0:torque=0.5@15", "L1:torque=0.5@15", "L2:torque=0.5@15", "L3:torque=0.5@15",
                        "R1:liar@25", "R2:liar@25"})
    args.insert(args.end(), {"--fault", f});
  auto r = run_cli(run_args(out, args), out, 600);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto& s = r.summary;
  EXPECT_EQ(s["status"], "ok");
  for (const char* t : {"L0", "L1", "L2", "L3", "R1", "R2"}) {
    const nlohmann::json* f = agent_fault(s, t);
    ASSERT_NE(f, nullptr) << t;
    EXPECT_FALSE((*f)["detected_s"].is_null()) << t << f->dump();
    EXPECT_FALSE((*f)["isolated_s"].is_null()) << t;
  }
  EXPECT_LT(s["plant"]["path"]["cross_track_max_m"].get<double>(), 0.5);
  EXPECT_EQ(s["plant"]["agent_faults"]["false_detections"], 0);
}

TEST(AgentFaults, AClearedFaultLetsTheAgentBackAfterItsProbation) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(run_args(out, {default_scenario(), "--duration", "35", "--fault", "L3:open@20", "--clear", "L3@22"}),
                   out, 300);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json* f = agent_fault(r.summary, "L3");
  ASSERT_NE(f, nullptr);
  ASSERT_FALSE((*f)["detected_s"].is_null());
  EXPECT_DOUBLE_EQ((*f)["cleared_s"].get<double>(), 22.0);
  ASSERT_FALSE((*f)["readmitted_s"].is_null()) << f->dump();
  // Probation: 10 s (control.fault_probation_s) from the isolation.
  EXPECT_NEAR((*f)["readmitted_s"].get<double>() - (*f)["detected_s"].get<double>(), 10.0, 0.02);
  EXPECT_EQ((*f)["relapses"], 0);  // healthy when let back: not flagged again
  EXPECT_EQ(r.summary["status"], "ok");
}

TEST(AgentFaults, AFaultNoGroupDetectsIsNotAnOkRun) {
  // Detection on, but a threshold above any current: the fault goes unseen, and the run says
  // so instead of ok (exit 3, degraded).
  TempDir tmp;
  const std::string scen = tmp.path() + "/slow.yaml";
  write_file(scen, "name: slow\nagents: 16\nduration_s: 25\ncontrol:\n  fault_current_A: 1000\n");
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(run_args(out, {scen, "--fault", "L3:open@20"}), out, 300);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_EQ(r.summary["status"], "degraded: fault open on L3 at 20.00 s not detected");
  const nlohmann::json* f = agent_fault(r.summary, "L3");
  ASSERT_NE(f, nullptr);
  EXPECT_TRUE((*f)["detected_s"].is_null());
}

TEST(AgentFaults, WithDetectionOffTheFaultRunsSilentAndTheTickCarriesNoMeasurements) {
  TempDir tmp;
  const std::string scen = tmp.path() + "/off.yaml";
  write_file(scen, "name: off\nagents: 16\nduration_s: 25\ncontrol:\n  fault_detection: false\n");
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(run_args(out, {scen, "--fault", "L3:open@20"}), out, 300);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json* f = agent_fault(r.summary, "L3");
  ASSERT_NE(f, nullptr);
  EXPECT_TRUE((*f)["detected_s"].is_null());
  EXPECT_TRUE((*f)["isolated_s"].is_null());
}
