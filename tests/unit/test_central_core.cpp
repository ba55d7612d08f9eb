// Central core (control/central_core.hpp): the path follower's wheel references at the next
// tick's time, its corrections against a robot off its path, and the relay of each group's
// active count to the other group.
#include <gtest/gtest.h>

#include <cmath>

#include "config/core_configs.hpp"
#include "config/scenario.hpp"
#include "control/central_core.hpp"
#include "control/path.hpp"
#include "model/kinematics.hpp"

namespace {

using maptr::control::CentralConfig;
using maptr::control::CentralCore;
using maptr::control::CentralInput;
using maptr::control::CentralOutput;
using maptr::control::Path;
using maptr::control::Pose;
using maptr::control::Segment;
using maptr::control::Trajectory;

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

/// Tick k's input with the robot exactly where the reference is at time t_ref.
CentralInput on_reference(const CentralConfig& c, double t_k, double t_ref) {
  CentralInput in;
  in.t_s = t_k;
  const auto ref = Path(c.trajectory).at_time(t_ref);
  in.pose = ref.pose;
  in.v_x = ref.v;
  return in;
}

TEST(CentralCore, OnAStraightLineTheCommandIsTheProfileToTheLastBit) {
  // The paper's experiments drive straight lines: with the robot on the path the follower adds
  // nothing, not even a -0, so their traces are those of the open-loop profile.
  CentralInput in = on_reference(mission(), 0.5, 0.5);
  in.pose.x -= 1.3;  // behind the reference, on the line
  const CentralOutput o = CentralCore(mission()).step(in);
  EXPECT_EQ(o.segment, 0);
  EXPECT_EQ(o.v_x_ref, 8.0);
  EXPECT_EQ(o.w_ref, 0.0);
  EXPECT_FALSE(std::signbit(o.w_ref));
  EXPECT_EQ(o.phidot_ref_L, 8.0 / 0.035);
  EXPECT_EQ(o.phidot_ref_R, 8.0 / 0.035);
}

TEST(CentralCore, OnTheArcTheCommandIsTheSkidSteerOfTheArc) {
  const CentralConfig c = mission();
  const CentralOutput o = CentralCore(c).step(on_reference(c, 1.5, 1.51));
  EXPECT_EQ(o.segment, 1);
  // phidot = (v -+ (a/2) w) / r = (4 -+ 0.05) / 0.035 rad/s.
  EXPECT_NEAR(o.phidot_ref_L, 3.95 / 0.035, 1e-9);
  EXPECT_NEAR(o.phidot_ref_R, 4.05 / 0.035, 1e-9);
  EXPECT_NEAR(o.cross_track_m, 0.0, 1e-9);
}

TEST(CentralCore, ReferenceIsTheOneAtTheNextTick) {
  const CentralConfig c = mission();
  const CentralCore core(c);
  // t_k = 0.985 s: t_k + dt = 0.995 s, still the straight; t_k = 0.995 s: 1.005 s, the arc.
  EXPECT_EQ(core.step(on_reference(c, 0.985, 0.985)).segment, 0);
  const CentralOutput o = core.step(on_reference(c, 0.995, 1.005));
  EXPECT_EQ(o.segment, 1);
  EXPECT_NEAR(o.phidot_ref_R - o.phidot_ref_L, 0.2 * 0.5 / 0.035, 1e-9);
  // After the mission: stop.
  const CentralOutput end = core.step(on_reference(c, 2.0, 2.0));
  EXPECT_EQ(end.segment, 2);
  EXPECT_EQ(end.phidot_ref_L, 0.0);
  EXPECT_EQ(end.phidot_ref_R, 0.0);
}

TEST(CentralCore, ARobotBesideTheLineIsSteeredBackSymmetrically) {
  const CentralConfig c = mission();
  CentralInput left = on_reference(c, 0.5, 0.5), right = left;
  left.pose.y = 0.3;
  right.pose.y = -0.3;
  const CentralOutput l = CentralCore(c).step(left), r = CentralCore(c).step(right);
  EXPECT_NEAR(l.cross_track_m, 0.3, 1e-12);
  EXPECT_LT(l.w_ref, 0.0);  // left of the path: turn right
  EXPECT_GT(r.w_ref, 0.0);
  EXPECT_NEAR(l.w_ref, -r.w_ref, 1e-12);
  // Heading towards theta_d = -atan(e / L), L = max(4 v / K, L_min) = 16 m at 8 m/s, K = 2 1/s.
  EXPECT_NEAR(l.w_ref, -2.0 * std::atan(0.3 / 16.0), 1e-12);
}

TEST(CentralCore, TheHeadingLoopAddsAtMostTheMaximumCorrection) {
  // 20 m beside a straight line at 8 m/s the heading loop wants K atan(20 / 16) = 1.79 rad/s.
  CentralConfig c = mission();
  CentralInput left = on_reference(c, 0.5, 0.5), right = left;
  left.pose.y = 20.0;
  right.pose.y = -20.0;
  for (const double bound : {1.0, 0.25}) {
    c.path_max_correction_rad_s = bound;
    EXPECT_DOUBLE_EQ(CentralCore(c).step(left).w_ref, -bound);
    EXPECT_DOUBLE_EQ(CentralCore(c).step(right).w_ref, bound);
  }
}

/// A kinematic robot (unicycle) that does what central commands, on a path of `segs`, started
/// off the path; returns the largest |cross-track| over the last `tail_s` seconds.
double follow(const std::vector<Segment>& segs, Pose start, double run_s, double tail_s, double gain = 2.0) {
  CentralConfig c;
  c.trajectory.segments = segs;
  c.path_heading_gain_1_s = gain;
  const CentralCore core(c);
  const Path path(c.trajectory);
  Pose x = start;
  double v = 0.0, worst = 0.0;
  for (int k = 0; k * c.dt_s < run_s; ++k) {
    const double t = k * c.dt_s;
    CentralInput in;
    in.t_s = t;
    in.pose = x;
    in.v_x = v;
    const CentralOutput o = core.step(in);
    v = o.v_x_ref;
    x.x += v * std::cos(x.theta) * c.dt_s;
    x.y += v * std::sin(x.theta) * c.dt_s;
    x.theta += o.w_ref * c.dt_s;
    if (t > run_s - tail_s) {
      const auto ref = path.at_time(t);
      worst = std::max(worst, std::fabs(path.project(x, ref.s + 2.0).cross_track));
    }
  }
  return worst;
}

/// The furthest a robot started 0.5 m left of a straight at 1 m/s goes past it (right of it), m,
/// with the follower's damping ratio `zeta` set through the scenario's field.
double overshoot(double zeta) {
  maptr::config::Scenario s;
  maptr::config::set_field(s, "control.path_damping", std::to_string(zeta), "test");
  CentralConfig c = maptr::config::central_config(s);
  c.trajectory.segments = {Segment{"straight", 1.0, 0.0, 30.0, ""}};
  const CentralCore core(c);
  const Path path(c.trajectory);
  Pose x{0.0, 0.5, 0.0};
  double worst = 0.0;
  for (int k = 0; k * c.dt_s < 30.0; ++k) {
    const CentralOutput o = core.step(CentralInput{k * c.dt_s, x, 1.0, 0, 0});
    x.x += o.v_x_ref * std::cos(x.theta) * c.dt_s;
    x.y += o.v_x_ref * std::sin(x.theta) * c.dt_s;
    x.theta += o.w_ref * c.dt_s;
    worst = std::max(worst, -path.project(x, x.x + 2.0).cross_track);
  }
  return worst;
}

TEST(CentralCore, TheScenariosDampingRatioShapesTheWayBackToThePath) {
  // zeta = 1 (the default): critically damped, never past the line; zeta = 0.5 (L = L_min at
  // K = 2, v = 1): underdamped, past it by about exp(-pi zeta / sqrt(1 - zeta^2)) = 16 % of the
  // 0.5 m offset.
  EXPECT_LT(overshoot(1.0), 2e-3);
  EXPECT_GT(overshoot(0.5), 0.04);
  EXPECT_LT(overshoot(0.5), 0.12);
}

TEST(CentralCore, TheFollowerConvergesOnAStraightAndOnACircle) {
  // Started 0.5 m left of a straight and 0.5 m outside a circle of radius 5 m (1 m/s): the
  // error decays (critically damped at K/2 = 1 rad/s) to millimetres in 20 s (what is left on
  // the circle is the Euler steps of this test's robot).
  const Segment line{"straight", 1.0, 0.0, 30.0, ""};
  EXPECT_LT(follow({line}, {0.0, 0.5, 0.0}, 30.0, 5.0), 1e-3);
  const Segment circle{"arc", 1.0, 1.0 / 5.0, 60.0, ""};
  EXPECT_LT(follow({circle}, {0.0, -0.5, 0.0}, 60.0, 20.0), 5e-3);
  // And it is the loop that does it: with a gain near 0 the offset stays.
  EXPECT_GT(follow({line}, {0.0, 0.5, 0.0}, 30.0, 5.0, 1e-4), 0.4);
}

TEST(Path, ReferencePoseOnArcsIsTheClosedForm) {
  Trajectory t;
  t.segments = {Segment{"straight", 1.0, 0.0, 20.0, ""}, Segment{"arc", 1.0, 0.25, 2.0 * M_PI, ""},
                Segment{"straight", 1.0, 0.0, 10.0, ""}, Segment{"arc", 1.0, -0.25, 2.0 * M_PI, ""},
                Segment{"straight", 1.0, 0.0, 20.0, ""}};
  const Path p(t);
  // 20 m, a quarter circle of 4 m to the left, 10 m, a quarter to the right, 20 m.
  EXPECT_NEAR(p.length(), 50.0 + 4.0 * M_PI, 1e-9);
  EXPECT_NEAR(p.end().x, 20.0 + 4.0 + 4.0 + 20.0, 1e-9);
  EXPECT_NEAR(p.end().y, 4.0 + 10.0 + 4.0, 1e-9);
  EXPECT_NEAR(p.end().theta, 0.0, 1e-12);
  const auto mid = p.at_time(20.0 + M_PI);  // half way round the first turn
  EXPECT_NEAR(mid.pose.x, 20.0 + 4.0 * std::sin(M_PI / 4), 1e-9);
  EXPECT_NEAR(mid.pose.y, 4.0 - 4.0 * std::cos(M_PI / 4), 1e-9);
  EXPECT_NEAR(mid.pose.theta, M_PI / 4, 1e-12);
  EXPECT_EQ(mid.segment, 1);
  // A point 0.3 m outside the first turn's middle projects onto it with e = -0.3 (right of it).
  const Pose out{mid.pose.x + 0.3 * std::sin(M_PI / 4), mid.pose.y - 0.3 * std::cos(M_PI / 4), M_PI / 4};
  const auto pr = p.project(out, 100.0);
  EXPECT_NEAR(pr.cross_track, -0.3, 1e-9);
  EXPECT_NEAR(pr.s, 20.0 + M_PI, 1e-9);
  EXPECT_NEAR(pr.kappa, 0.25, 1e-12);
  // The search stops at s_max: the same point judged with only the first 10 m sent.
  EXPECT_NEAR(p.project(out, 10.0).s, 10.0, 1e-12);
}

TEST(Path, TheRampKeepsTheRadius) {
  Trajectory t;
  t.accel_mps2 = 0.5;
  t.segments = {Segment{"arc", 2.0, 0.5, 10.0, ""}};  // radius 4 m
  const Path p(t);
  const auto r = p.at_time(1.0);  // v = 0.5 m/s under the ramp
  EXPECT_NEAR(r.v, 0.5, 1e-12);
  EXPECT_NEAR(r.w, 0.5 / 4.0, 1e-12);
  EXPECT_NEAR(r.s, 0.25, 1e-12);
  const auto late = p.at_time(6.0);  // ramp done at 4 s: 4 m, then 2 m/s
  EXPECT_NEAR(late.s, 4.0 + 4.0, 1e-12);
  EXPECT_EQ(late.w, 0.5);
}

TEST(CentralCore, RelaySwapsTheCounts) {
  CentralInput in = on_reference(mission(), 0.5, 0.5);
  in.n_active_L = 3;
  in.n_active_R = 5;
  const CentralOutput o = CentralCore(mission()).step(in);
  EXPECT_EQ(o.relay_for_L, 5);  // the left group hears the right group's count
  EXPECT_EQ(o.relay_for_R, 3);
}

}  // namespace
