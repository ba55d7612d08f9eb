// Reach (model/reach.hpp): what steady turns the robot holds with each driver, and the
// scenario's check of every turn before anything starts (config/scenario.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "config/scenario.hpp"
#include "model/dynamics.hpp"
#include "model/reach.hpp"

namespace {

namespace mm = maptr::model;

mm::RobotParams robot(double kg, bool bidirectional) {
  mm::RobotParams p;
  p.gross_mass_kg = kg;
  p.driver.bidirectional = bidirectional;
  return p;
}

TEST(Reach, AStraightLineIsHeldAndTheTurnTorquesAreTheSidesShare) {
  const mm::RobotParams p = robot(30.0, false);
  const mm::TurnCheck s = mm::steady_turn(p, 1.0, 0.0, 23.4);
  EXPECT_TRUE(s.feasible);
  EXPECT_NEAR(s.tau_needed_L, s.tau_needed_R, 1e-15);
  // A left turn: the inner (left) side needs less than the outer, below zero when tight.
  const mm::TurnCheck t = mm::steady_turn(robot(30.0, true), 1.0, 0.25, 23.4);
  EXPECT_TRUE(t.feasible) << t.limit;
  EXPECT_LT(t.tau_needed_L, 0.0);
  EXPECT_GT(t.tau_needed_R, 0.0);
  EXPECT_NEAR(t.tau_needed_L + t.tau_needed_R,
              p.wheel_radius_m * mm::body_resistances(p, 1.0, 0.25).f_rx, 1e-12);
}

TEST(Reach, TheUnidirectionalDriverCannotBrakeSoItsTurnsAreWide) {
  for (double kg : {13.2, 30.0}) {
    const double uni = mm::tightest_radius(robot(kg, false), 5.0, 23.4);
    const double bi = mm::tightest_radius(robot(kg, true), 5.0, 23.4);
    EXPECT_GT(uni, 50.0) << kg;   // the inner side only free-wheels: a wide turn
    // A braking inner side: the bound is lateral friction, v^2 / R <= mu_l g (25.5 m at 5 m/s).
    EXPECT_NEAR(bi, 25.0 / (0.1 * 9.81), 0.01) << kg;
    EXPECT_LT(mm::tightest_radius(robot(kg, true), 1.0, 23.4), 1.1) << kg;
    // Just inside the bound is held, just outside is not.
    EXPECT_TRUE(mm::steady_turn(robot(kg, false), 5.0, 5.0 / (uni * 1.001), 23.4).feasible);
    EXPECT_FALSE(mm::steady_turn(robot(kg, false), 5.0, 5.0 / (uni * 0.999), 23.4).feasible);
  }
  // A heavier robot needs a wider turn (more lateral friction to overcome).
  EXPECT_GT(mm::tightest_radius(robot(30.0, false), 5.0, 23.4), mm::tightest_radius(robot(13.2, false), 5.0, 23.4));
}

TEST(Reach, LateralAccelerationIsBoundedByLateralFriction) {
  // mu_l g = 0.981 m/s^2: at 3 m/s a radius of 5 m asks 1.8 m/s^2.
  const mm::TurnCheck c = mm::steady_turn(robot(13.2, true), 3.0, 3.0 / 5.0, 23.4);
  EXPECT_FALSE(c.feasible);
  EXPECT_NE(c.limit.find("lateral"), std::string::npos);
}

std::string refusal(const std::string& yaml) {
  try {
    maptr::config::parse_scenario(yaml, "turn.yaml").validate();
  } catch (const maptr::config::ScenarioError& e) {
    return e.what();
  }
  return "";
}

const char* kLoop =
    "agents: 16\ngross_mass_kg: 30\nduration_s: 70\n"
    "trajectory:\n  segments:\n"
    "    - {type: straight, speed_mps: 1, duration_s: 20}\n"
    "    - {type: arc, speed_mps: 1, radius_m: 4, duration_s: 6.283185307179586}\n"
    "    - {type: straight, speed_mps: 1, duration_s: 10}\n"
    "    - {type: arc, speed_mps: 1, radius_m: -4, duration_s: 6.283185307179586}\n"
    "    - {type: straight, speed_mps: 1, duration_s: 20}\n";

TEST(Reach, ATurnOutOfReachIsRefusedNamingTheSegmentAndTheBound) {
  // The warehouse loop: held with the H-bridge, refused with the paper's driver.
  EXPECT_EQ(refusal(std::string(kLoop) + "robot: {driver: bidirectional}\n"), "");
  const std::string m = refusal(std::string(kLoop) + "robot: {driver: unidirectional}\n");
  EXPECT_NE(m.find("trajectory.segments[1].radius_m = 4: at 1 m/s with the unidirectional driver and 30 kg the "
                   "tightest reachable radius is "),
            std::string::npos)
      << m;
  // The newcomer's 20 m arc at 5 m/s, 24 agents.
  const std::string n = refusal(
      "agents: 24\ngross_mass_kg: 30\nduration_s: 30\ntrajectory:\n  segments:\n"
      "    - {type: straight, speed_mps: 5, duration_s: 10}\n"
      "    - {type: arc, speed_mps: 5, radius_m: 20, duration_s: 10}\n");
  EXPECT_NE(n.find("trajectory.segments[1].radius_m = 20: at 5 m/s with the unidirectional driver"), std::string::npos)
      << n;
  // Given by yaw rate, the yaw rate is named.
  const std::string w = refusal(
      "gross_mass_kg: 30\ntrajectory:\n  segments:\n    - {type: arc, speed_mps: 5, yaw_rate_rad_s: 0.25, "
      "duration_s: 10}\n");
  EXPECT_NE(w.find("trajectory.segments[0].yaw_rate_rad_s = 0.25"), std::string::npos) << w;
}

TEST(Reach, RegenerationNeedsTheBidirectionalDriver) {
  const std::string m = refusal("robot: {driver: unidirectional, regeneration: true}\n");
  EXPECT_NE(m.find("robot.regeneration = true: only a bidirectional driver"), std::string::npos) << m;
  EXPECT_EQ(refusal("robot: {driver: bidirectional, regeneration: true}\n"), "");
}

TEST(Waypoints, ARouteOfPointsIsTheStraightsAndArcsItRounds) {
  const auto arcs = maptr::config::parse_scenario(std::string(kLoop) + "robot: {driver: bidirectional}\n", "a.yaml");
  // The same loop as points (one more on the first straight), corners rounded with 4 m.
  const auto route = maptr::config::parse_scenario(
      "agents: 16\ngross_mass_kg: 30\nduration_s: 70\nrobot: {driver: bidirectional}\n"
      "trajectory:\n  segments:\n"
      "    - {type: waypoints, speed_mps: 1, corner_radius_m: 4, points: [[10, 0], [24, 0], [24, 18], [48, 18]]}\n",
      "w.yaml");
  const auto& a = arcs.trajectory.segments;
  const auto& b = route.trajectory.segments;
  // 10 + 10 m straight (the point at 10 m splits it), quarter left, 10 m, quarter right, 20 m.
  ASSERT_EQ(b.size(), 6u);
  EXPECT_NEAR(b[0].duration_s + b[1].duration_s, a[0].duration_s, 1e-9);
  for (std::size_t i = 1; i < a.size(); ++i) {
    EXPECT_EQ(b[i + 1].type, a[i].type) << i;
    EXPECT_NEAR(b[i + 1].yaw_rate_rad_s, a[i].yaw_rate_rad_s, 1e-12) << i;
    EXPECT_NEAR(b[i + 1].duration_s, a[i].duration_s, 1e-9) << i;
  }
  route.validate();
}

TEST(Waypoints, BadRoutesAreRefusedNamingThePoint) {
  auto route = [](const std::string& seg) {
    return refusal("robot: {driver: bidirectional}\ntrajectory:\n  segments:\n    - " + seg + "\n");
  };
  EXPECT_NE(route("{type: waypoints, speed_mps: 1, points: [[0, 0], [0, 5]]}").find("points[1]"), std::string::npos);
  EXPECT_NE(route("{type: waypoints, speed_mps: 1, corner_radius_m: 4, points: [[0, 0], [2, 0], [2, 5]]}")
                .find("trajectory.segments[0].points[1] = (too close): corner_radius_m = 4 needs 4 m"),
            std::string::npos);
  EXPECT_NE(route("{type: waypoints, speed_mps: 1, points: [[0, 0], [5, 0], [0, 0]]}").find("turns back"),
            std::string::npos);
  EXPECT_NE(route("{type: waypoints, speed_mps: 1, points: [[0, 0], [5, x]]}").find("points[1]"), std::string::npos);
  EXPECT_NE(route("{type: waypoints, speed_mps: 1, duration_s: 3, points: [[0, 0], [5, 0]]}").find("duration_s"),
            std::string::npos);
  EXPECT_NE(route("{type: straight, speed_mps: 1, duration_s: 3, points: [[0, 0], [5, 0]]}").find("only a waypoints"),
            std::string::npos);
}

}  // namespace
