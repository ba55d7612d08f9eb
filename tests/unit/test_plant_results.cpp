// plant.json (records/plant_results.hpp): what the plant writes the launcher reads back field for
// field; a missing or cut-short file is no results; a key of the wrong type names the file.
#include <gtest/gtest.h>

#include <fstream>

#include "records/csv.hpp"
#include "records/plant_results.hpp"
#include "records/run_files.hpp"
#include "tests/unit/unit_temp_dir.hpp"

namespace {

using maptr::records::PlantResults;

PlantResults sample() {
  PlantResults r;
  r.status = "degraded: path not followed";
  r.end_reason = "duration reached";
  r.sim_time_s = 20.0;
  r.ticks = 2000;
  r.active_agents = {5, 6};
  r.agent_active_s = {{1.0, 2.0}, {3.0}};
  r.path.cross_track_max_m = 0.75;
  r.rejected_by_kind = {{"forged", 2}};
  r.answers_taken = {{"maptr/agent_reply", 32000}};
  r.membership_events = {{"L1", "died (launcher)", 5.0, 123.5}};
  maptr::records::AgentFaultRecord f;
  f.target = "L2";
  f.mode = "open";
  f.injected_s = 4.0;
  f.detected_s = 4.25;
  f.exposed_ticks = 25;
  r.agent_faults.faults = {f};
  r.agent_faults.diagnoses = {{4.25, "L2", "isolated", "open", false}};
  r.group_wear = {{"L", {{"steps_back", 0}}}};
  return r;
}

TEST(PlantResults, WhatThePlantWritesIsReadBackFieldForField) {
  const maptr::testing::UnitTempDir tmp("plant_results");
  const PlantResults r = sample();
  maptr::records::write_plant_results(tmp.path(), r);
  const auto back = maptr::records::read_plant_results(tmp.path());
  ASSERT_TRUE(back);
  EXPECT_EQ(maptr::records::to_json(*back), maptr::records::to_json(r));
  EXPECT_EQ(back->status, "degraded: path not followed");
  EXPECT_EQ(back->ticks, 2000);
  EXPECT_EQ(back->active_agents.R, 6);
  EXPECT_EQ(back->agent_active_s.L.size(), 2u);
  EXPECT_DOUBLE_EQ(back->path.cross_track_max_m, 0.75);
  ASSERT_EQ(back->agent_faults.faults.size(), 1u);
  EXPECT_EQ(back->agent_faults.faults[0].detected_s, std::optional<double>(4.25));
  EXPECT_FALSE(back->agent_faults.faults[0].isolated_s);
  EXPECT_EQ(back->membership_events[0].name, "L1");
}

TEST(PlantResults, AbsentValuesAreNullInTheFile) {
  const nlohmann::json j = maptr::records::to_json(sample());
  EXPECT_TRUE(j["agent_faults"]["faults"][0]["isolated_s"].is_null());
  EXPECT_TRUE(j["agent_faults"]["faults"][0]["diagnosed_mode"].is_null());
  EXPECT_EQ(j["active_agents"], nlohmann::json({{"L", 5}, {"R", 6}}));
}

TEST(PlantResults, NoFileOrACutShortOneIsNoResultsAndAWrongTypeNamesTheFile) {
  const maptr::testing::UnitTempDir tmp("plant_results_bad");
  EXPECT_FALSE(maptr::records::read_plant_results(tmp.path()));
  const std::string path = maptr::records::plant_results_path(tmp.path());
  std::ofstream(path) << "{\"status\": \"ok\", \"ticks\": ";
  EXPECT_FALSE(maptr::records::read_plant_results(tmp.path()));
  std::ofstream(path) << R"({"status": "ok", "ticks": "many"})";
  try {
    maptr::records::read_plant_results(tmp.path());
    ADD_FAILURE() << "a text where a count belongs was read";
  } catch (const maptr::records::RecordError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  // Keys the file lacks read as their defaults (a plant of an earlier version).
  std::ofstream(path) << R"({"status": "ok", "sim_time_s": 3.5})";
  const auto r = maptr::records::read_plant_results(tmp.path());
  ASSERT_TRUE(r);
  EXPECT_DOUBLE_EQ(r->sim_time_s, 3.5);
  EXPECT_EQ(r->loop_scheduling, "normal");
}

}  // namespace
