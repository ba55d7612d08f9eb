// Central core (control/central_core.hpp): wheel references from the kinematics at the next
// tick's time, and the relay of each group's active count to the other group.
#include <gtest/gtest.h>

#include "control/central_core.hpp"

namespace {

using maptr::control::CentralConfig;
using maptr::control::CentralCore;
using maptr::control::CentralOutput;
using maptr::control::Segment;

/// 1 s straight at 8 m/s, then 1 s of arc at 4 m/s and 0.5 rad/s; a = 0.2 m, r = 0.035 m.
CentralConfig mission() {
  CentralConfig c;
  Segment straight;
  straight.speed_mps = 8.0;
  straight.duration_s = 1.0;
  Segment arc;
  arc.type = "arc";
  arc.speed_mps = 4.0;
  arc.yaw_rate_rad_s = 0.5;
  arc.duration_s = 1.0;
  c.trajectory.segments = {straight, arc};
  c.dt_s = 0.01;
  c.track_m = 0.2;
  c.wheel_radius_m = 0.035;
  return c;
}

TEST(CentralCore, StraightSegmentGivesEqualWheelReferences) {
  const CentralOutput o = CentralCore(mission()).step(0.5, 0, 0);
  EXPECT_EQ(o.segment, 0);
  EXPECT_EQ(o.v_x_ref, 8.0);
  EXPECT_EQ(o.w_ref, 0.0);
  EXPECT_NEAR(o.phidot_ref_L, 8.0 / 0.035, 1e-12);
  EXPECT_NEAR(o.phidot_ref_R, 8.0 / 0.035, 1e-12);
}

TEST(CentralCore, ArcSegmentGivesTheSkidSteerWheelReferences) {
  const CentralOutput o = CentralCore(mission()).step(1.5, 0, 0);
  EXPECT_EQ(o.segment, 1);
  // phidot = (v -+ (a/2) w) / r = (4 -+ 0.05) / 0.035 rad/s.
  EXPECT_NEAR(o.phidot_ref_L, 3.95 / 0.035, 1e-12);
  EXPECT_NEAR(o.phidot_ref_R, 4.05 / 0.035, 1e-12);
}

TEST(CentralCore, ReferenceIsTheOneAtTheNextTick) {
  const CentralCore core(mission());
  // t_k = 0.985 s: t_k + dt = 0.995 s, still the straight; t_k = 0.995 s: 1.005 s, the arc.
  EXPECT_EQ(core.step(0.985, 0, 0).segment, 0);
  const CentralOutput o = core.step(0.995, 0, 0);
  EXPECT_EQ(o.segment, 1);
  EXPECT_NEAR(o.phidot_ref_R - o.phidot_ref_L, 0.2 * 0.5 / 0.035, 1e-12);
  // After the mission: stop.
  const CentralOutput end = core.step(2.0, 0, 0);
  EXPECT_EQ(end.segment, 2);
  EXPECT_EQ(end.phidot_ref_L, 0.0);
  EXPECT_EQ(end.phidot_ref_R, 0.0);
}

TEST(CentralCore, RelaySwapsTheCounts) {
  const CentralOutput o = CentralCore(mission()).step(0.5, 3, 5);
  EXPECT_EQ(o.relay_for_L, 5);  // the left group hears the right group's count
  EXPECT_EQ(o.relay_for_R, 3);
}

}  // namespace
