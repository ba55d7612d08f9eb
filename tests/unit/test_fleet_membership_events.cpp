// summary.json's membership_events (deploy/fleet/membership_events.hpp): every change the plant
// recorded, with its kind, process, times and cause from the launcher's fault records.
#include <gtest/gtest.h>

#include "deploy/fleet/membership_events.hpp"

namespace {

using nlohmann::json;
using namespace maptr::deploy;

json plant_event(const std::string& name, const std::string& event, double t_s, double wall_ms) {
  return {{"name", name}, {"event", event}, {"t_s", t_s}, {"wall_ms", wall_ms}};
}

json fault(const std::string& target, const std::string& action, double at_s, const std::string& origin) {
  return {{"target", target}, {"action", action}, {"at_s", at_s}, {"wall_ms", 1.0}, {"origin", origin}};
}

TEST(FleetMembershipEvents, KindsOfThePlantsRecords) {
  EXPECT_EQ(membership_kind("died (launcher)"), "died");
  EXPECT_EQ(membership_kind("lost (DDS liveliness)"), "lease_lost");
  EXPECT_EQ(membership_kind("missed the tick deadline"), "deadline_missed");
  EXPECT_EQ(membership_kind("paused (launcher)"), "paused");
  EXPECT_EQ(membership_kind("resumed (launcher)"), "resumed");
  EXPECT_EQ(membership_kind("started (launcher)"), "started");
  EXPECT_EQ(membership_kind("rejoined"), "rejoined");
  EXPECT_EQ(membership_kind("something new"), "something new");
}

TEST(FleetMembershipEvents, APauseAndItsResumeByChaosThenTheRejoin) {
  const json plant = json::array({plant_event("L1", "paused (launcher)", 5.0, 1000.0),
                                  plant_event("L1", "resumed (launcher)", 8.0, 1600.0),
                                  plant_event("L1", "rejoined", 8.01, 1650.0)});
  const json failures =
      json::array({fault("L1", "pause", 5.0, "chaos"), fault("L1", "resume", 8.0, "chaos")});
  const json e = membership_events(plant, failures);
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(
      e[0],
      json({{"kind", "paused"}, {"process", "L1"}, {"t_s", 5.0}, {"wall_ms", 1000.0}, {"cause", "chaos"}}));
  EXPECT_EQ(e[1]["kind"], "resumed");
  EXPECT_EQ(e[1]["cause"], "chaos");
  EXPECT_EQ(e[2]["kind"], "rejoined");
  EXPECT_EQ(e[2]["after"], "resumed");
  EXPECT_EQ(e[2]["cause"], "chaos");
  EXPECT_DOUBLE_EQ(e[2]["t_s"].get<double>(), 8.01);
  EXPECT_DOUBLE_EQ(e[2]["wall_ms"].get<double>(), 1650.0);
}

TEST(FleetMembershipEvents, CausesOfDeathsLeasesAndDeadlines) {
  const json plant = json::array({plant_event("L1", "died (launcher)", 5.0, 1.0),         // scheduled kill
                                  plant_event("L1", "started (launcher)", 8.0, 2.0),      // its restart
                                  plant_event("R0", "died (launcher)", 9.0, 3.0),         // nobody asked
                                  plant_event("R3", "lost (DDS liveliness)", 10.0, 4.0),  // external SIGSTOP
                                  plant_event("R3", "rejoined", 14.0, 5.0),               // external SIGCONT
                                  plant_event("group-L", "missed the tick deadline", 15.0, 6.0),
                                  plant_event("central", "died (launcher)", 16.0, 7.0)});  // `maptr kill`
  const json failures =
      json::array({fault("L1", "kill", 5.0, "scheduled"),
                   fault("L1", "restart", 8.0, "scheduled"),
                   fault("central", "kill", 16.0, "command"),
                   // skipped faults explain nothing
                   {{"target", "R0"}, {"action", "kill"}, {"at_s", 9.0}, {"skipped", "not running"}}});
  const json e = membership_events(plant, failures);
  ASSERT_EQ(e.size(), 7u);
  const std::vector<std::string> causes = {"scheduled", "scheduled", "external signal", "lease",
                                           "lease",     "deadline",  "command"};
  for (std::size_t i = 0; i < e.size(); ++i) EXPECT_EQ(e[i]["cause"], causes[i]) << e[i].dump();
  EXPECT_EQ(e[3]["kind"], "lease_lost");
  EXPECT_EQ(e[4]["after"], "lease_lost");
}

TEST(FleetMembershipEvents, EachFaultExplainsOneChangeOnly) {
  // Two kills of L1 at 5 s and 20 s: the second death is explained by the second kill only.
  const json plant = json::array({plant_event("L1", "died (launcher)", 5.0, 1.0),
                                  plant_event("L1", "died (launcher)", 20.0, 2.0),
                                  plant_event("L1", "died (launcher)", 30.0, 3.0)});
  const json failures =
      json::array({fault("L1", "kill", 5.0, "scheduled"), fault("L1", "kill", 20.0, "chaos")});
  const json e = membership_events(plant, failures);
  EXPECT_EQ(e[0]["cause"], "scheduled");
  EXPECT_EQ(e[1]["cause"], "chaos");
  EXPECT_EQ(e[2]["cause"], "external signal");
}

}  // namespace
