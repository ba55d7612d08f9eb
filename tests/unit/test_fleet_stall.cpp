// The launcher's stall watchdog (deploy/fleet/stall_watch.hpp) and the soak's deadline for a
// fleet's launcher (deploy/fleet/soak.hpp), on explicit wall times.
#include <gtest/gtest.h>

#include "deploy/fleet/soak.hpp"
#include "deploy/fleet/stall_watch.hpp"

namespace {

using maptr::deploy::fleet::stalled_status;
using maptr::deploy::fleet::StallWatch;
namespace soak = maptr::deploy::soak;

TEST(StallWatch, NotStalledBeforeTheStart) {
  StallWatch w(10.0);
  EXPECT_FALSE(w.stalled(1e6));
}

TEST(StallWatch, StallsAfterTheLimitWithoutATick) {
  StallWatch w(10.0);
  w.start(100.0);
  w.observe(0.0, 0, 100.0);
  EXPECT_FALSE(w.stalled(110.0));
  EXPECT_TRUE(w.stalled(110.5));
  EXPECT_NEAR(w.idle_s(110.5), 10.5, 1e-12);
}

TEST(StallWatch, EachLaterTickRestartsTheWait) {
  StallWatch w(10.0);
  w.start(0.0);
  for (int k = 1; k <= 5; ++k) w.observe(0.01 * k, 0, 8.0 * k);  // a slow plant: 8 s per tick
  EXPECT_FALSE(w.stalled(49.0));
  EXPECT_TRUE(w.stalled(50.5));
  EXPECT_NEAR(w.last_t_sim_s(), 0.05, 1e-12);
}

TEST(StallWatch, TheSameTickAgainIsNoProgress) {
  // A plant that publishes the same tick again (repairs) while nobody answers is stuck.
  StallWatch w(10.0);
  w.start(0.0);
  w.observe(3.0, 0, 1.0);
  for (double now = 2.0; now < 20.0; now += 1.0) w.observe(3.0, 0, now);
  EXPECT_TRUE(w.stalled(11.5));
}

TEST(StallWatch, AGateAndTheLaunchersOwnHoldAreProgress) {
  StallWatch w(10.0);
  w.start(0.0);
  w.observe(5.0, 0, 1.0);
  w.observe(5.0, 1, 9.0);  // a fault gate at the time of the last tick
  EXPECT_FALSE(w.stalled(18.0));
  w.held_until(40.0);  // the launcher answered the gate (restarts) until 40 s
  EXPECT_FALSE(w.stalled(49.0));
  EXPECT_TRUE(w.stalled(50.5));
}

TEST(StallWatch, StatusNamesTheLimitAndTheLastTime) {
  StallWatch w(180.0);
  w.start(0.0);
  w.observe(12.34, 0, 1.0);
  const std::string st = stalled_status(w);
  EXPECT_EQ(st.rfind("aborted: stalled: ", 0), 0u) << st;
  EXPECT_NE(st.find("180 s"), std::string::npos) << st;
  EXPECT_NE(st.find("t=12.34 s"), std::string::npos) << st;
  EXPECT_FALSE(soak::check_status({{"status", st}}).empty());  // a soak counts it as a failure
}

TEST(SoakDeadline, TermAfterTheTimeoutThenKillAfterTheGrace) {
  EXPECT_EQ(soak::fleet_deadline(599.0, 600.0, 60.0), soak::Deadline::kNone);
  EXPECT_EQ(soak::fleet_deadline(600.5, 600.0, 60.0), soak::Deadline::kTerm);
  EXPECT_EQ(soak::fleet_deadline(659.0, 600.0, 60.0), soak::Deadline::kTerm);
  EXPECT_EQ(soak::fleet_deadline(660.5, 600.0, 60.0), soak::Deadline::kKill);
}

TEST(SoakDeadline, AMissingSummaryIsAFailedStatus) {
  EXPECT_NE(soak::check_status(nlohmann::json::object()).find("missing"), std::string::npos);
}

}  // namespace
