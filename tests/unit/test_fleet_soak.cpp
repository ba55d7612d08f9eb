// The checks of `maptr soak` (deploy/fleet/soak.hpp) on given summaries and ledger files.
#include <gtest/gtest.h>

#include <filesystem>

#include "deploy/fleet/soak.hpp"
#include "records/ledger_file.hpp"

namespace {

using nlohmann::json;
using namespace maptr::deploy::soak;

/// A summary whose plant saw the given last ledgers and regressions.
json summary_with_wear(const std::vector<double>& l, const std::vector<double>& r, int regressions = 0) {
  return {
      {"plant",
       {{"group_wear",
         {{"L", {{"wear_m", l}, {"regressions", regressions}, {"largest_drop_m", regressions ? 0.5 : 0.0}}},
          {"R", {{"wear_m", r}, {"regressions", 0}, {"largest_drop_m", 0.0}}}}}}}};
}

struct SoakWear : ::testing::Test {
  std::string dir = ::testing::TempDir() + "/soak_wear";
  void SetUp() override {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  void TearDown() override { std::filesystem::remove_all(dir); }
  /// The group of `side` kept a ledger with this wear (records/ledger_file.hpp).
  void ledger(const std::string& side, const std::vector<double>& wear) {
    maptr::control::Ledger l(static_cast<int>(wear.size()));
    l.wear_m = wear;
    maptr::records::save_ledger(maptr::records::ledger_path(dir, side == "L" ? 0 : 1), l);
  }
};

TEST(Soak, StatusOkOrDegradedWithAReason) {
  EXPECT_EQ(check_status({{"status", "ok"}}), "");
  EXPECT_EQ(check_status({{"status", "degraded: side L has no live agent; the robot stopped"}}), "");
  EXPECT_NE(check_status({{"status", "degraded: "}}), "");
  EXPECT_NE(check_status({{"status", "aborted: interrupted"}}), "");
  EXPECT_NE(check_status(json::object()), "");
}

TEST_F(SoakWear, LedgersKeptAndNeverBackwardsPass) {
  ledger("L", {1.0, 2.0});
  ledger("R", {3.0, 0.0});
  EXPECT_TRUE(check_wear(summary_with_wear({1.0, 1.5}, {3.0, 0.0}), dir, 2).empty());
}

TEST_F(SoakWear, ARegressionALostFileAndLostWearFail) {
  ledger("L", {1.0, 2.0});
  const auto regress = check_wear(summary_with_wear({1.0, 2.0}, {0.0, 0.0}, 2), dir, 2);
  ASSERT_EQ(regress.size(), 2u);  // group-L went backwards; group-R's file is missing
  EXPECT_NE(regress[0].find("group-L: the wear ledger went backwards 2 times"), std::string::npos)
      << regress[0];
  EXPECT_NE(regress[1].find("group-R: ledger"), std::string::npos) << regress[1];
  ledger("R", {0.5, 4.0});
  const auto lost = check_wear(summary_with_wear({1.0, 2.0}, {0.5, 4.5}), dir, 2);
  ASSERT_EQ(lost.size(), 1u);
  EXPECT_NE(lost[0].find("agent 1's wear 4.0"), std::string::npos) << lost[0];
  ledger("R", {0.5, 4.0, 1.0});
  EXPECT_EQ(check_wear(summary_with_wear({1.0, 2.0}, {0.5, 4.0}), dir, 2).size(), 1u);  // wrong size
}

TEST(Soak, DistanceAndEnergyWithinTheBand) {
  const json ref = {{"distance_m", 400.0}, {"energy_J", 10000.0}};
  Band b;
  b.distance_below_pct = 30.0;
  b.distance_above_pct = 2.0;
  b.energy_pct = 20.0;
  EXPECT_DOUBLE_EQ(deviation_pct(300.0, 400.0), -25.0);
  EXPECT_TRUE(check_band({{"distance_m", 300.0}, {"energy_J", 8500.0}}, ref, b).empty());
  EXPECT_EQ(check_band({{"distance_m", 270.0}, {"energy_J", 10000.0}}, ref, b).size(), 1u);  // -32.5 %
  EXPECT_EQ(check_band({{"distance_m", 412.0}, {"energy_J", 10000.0}}, ref, b).size(), 1u);  // +3 %
  EXPECT_EQ(check_band({{"distance_m", 400.0}, {"energy_J", 12500.0}}, ref, b).size(), 1u);  // +25 %
}

TEST(Soak, AHealthyAgentIsolatedFailsTheDetectionCheck) {
  const json clean = {{"plant", {{"agent_faults", {{"diagnoses", json::array({{{"target", "L1"},
                                                                               {"diagnosed", "open"},
                                                                               {"t_s", 12.5},
                                                                               {"false_detection", false}}})}}}}}};
  EXPECT_TRUE(check_detection(clean).empty());
  json bad = clean;
  bad["plant"]["agent_faults"]["diagnoses"][0]["false_detection"] = true;
  const auto why = check_detection(bad);
  ASSERT_EQ(why.size(), 1u);
  EXPECT_NE(why[0].find("L1 isolated as open at 12.5"), std::string::npos) << why[0];
  EXPECT_TRUE(check_detection(json::object()).empty());  // a summary without the record
}

TEST(Soak, FaultsCountedByKindAndSkipped) {
  const json s = {{"failures", json::array({{{"action", "kill"}},
                                            {{"action", "restart"}},
                                            {{"action", "pause"}},
                                            {{"action", "resume"}},
                                            {{"action", "kill"}},
                                            {{"action", "restart"}, {"skipped", "x"}}})}};
  const auto n = faults_by_kind(s);
  EXPECT_EQ(n.at("kill"), 2);
  EXPECT_EQ(n.at("restart"), 1);
  EXPECT_EQ(n.at("pause"), 1);
  EXPECT_EQ(n.at("resume"), 1);
  EXPECT_EQ(n.at("skipped"), 1);
}

TEST(Soak, EachFleetHasItsOwnReproducibleSchedule) {
  maptr::config::Scenario sc;
  sc.robot.agents = 8;
  sc.duration_s = 40.0;
  const auto a = fleet_faults(5, 0, sc, 8), again = fleet_faults(5, 0, sc, 8),
             next = fleet_faults(5, 1, sc, 8);
  ASSERT_FALSE(a.empty());
  ASSERT_EQ(a.size(), again.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    EXPECT_EQ(a[i].target + a[i].action, again[i].target + again[i].action);
  EXPECT_NE(fleet_seed(5, 0), fleet_seed(5, 1));
  EXPECT_NE(fleet_seed(5, 0), fleet_seed(6, 0));
  bool differs = a.size() != next.size();
  for (std::size_t i = 0; !differs && i < a.size(); ++i) differs = a[i].at_s != next[i].at_s;
  EXPECT_TRUE(differs);
  sc.faults = a;
  EXPECT_NO_THROW(sc.validate());
}

}  // namespace
