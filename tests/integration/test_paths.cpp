// Paths on real fleets (ctest label `integration`): the warehouse loop of the default scenario
// followed in closed loop with the bidirectional driver, in both modes; turns out of reach
// refused before anything starts; a waypoint route tracked like the arcs it stands for; agents
// of the outer side killed in a turn; the reach bound against a fleet at the bound.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "config/scenario.hpp"
#include "model/battery.hpp"
#include "model/reach.hpp"
#include "records/trace.hpp"
#include "tests/integration/fleet_runner.hpp"

namespace {

using namespace maptr::testing;

const std::string kDefault = std::string(MAPTR_SOURCE_DIR) + "/deploy/scenarios/default.yaml";

/// `maptr run SCENARIO EXTRA...` into tmp/NAME; the result with its summary.
CliResult run_loop(const TempDir& tmp, const std::string& name, const std::string& scenario,
                   std::vector<std::string> extra = {}) {
  const std::string out = tmp.path() + "/" + name;
  extra.insert(extra.begin(), scenario);
  return run_cli(run_args(out, extra), out, 600);
}

double path_figure(const CliResult& r, const char* key) { return r.summary["path"][key].get<double>(); }

/// |heading - heading of the straight| half a second before each straight of the loop ends
/// (t = 20.5, 36.8, 63.1 s: the reference reaches the ends at 21, 37.3, 63.6 s).
double worst_heading_at_straight_ends(const std::string& run_dir) {
  const struct {
    double t, heading;
  } ends[] = {{20.5, 0.0}, {36.8, M_PI / 2}, {63.1, 0.0}};
  double worst = 0.0;
  for (const auto& row : maptr::records::read_trace(run_dir + "/trace.csv"))
    for (const auto& e : ends)
      if (std::fabs(row.t_s - e.t) < 0.005) worst = std::max(worst, std::fabs(row.theta_rad - e.heading));
  return worst;
}

TEST(Paths, TheWarehouseLoopIsFollowedInBothModesAndRepeats) {
  TempDir tmp;
  const CliResult ec = run_loop(tmp, "ec", kDefault, {"--mode", "ec"});
  ASSERT_EQ(ec.exit_code, 0) << ec.output;
  const CliResult ec2 = run_loop(tmp, "ec2", kDefault, {"--mode", "ec"});
  ASSERT_EQ(ec2.exit_code, 0) << ec2.output;
  const CliResult all = run_loop(tmp, "all", kDefault, {"--mode", "all"});
  ASSERT_EQ(all.exit_code, 0) << all.output;
  for (const CliResult* r : {&ec, &all}) {
    EXPECT_EQ(r->summary["status"], "ok");
    EXPECT_LE(path_figure(*r, "cross_track_max_m"), 0.2) << r->run_dir;
    EXPECT_LE(worst_heading_at_straight_ends(r->run_dir), 0.1) << r->run_dir;
    EXPECT_LE(path_figure(*r, "final_position_error_m"), 0.5) << r->run_dir;
    EXPECT_NEAR(r->summary["distance_m"].get<double>(), 50.0 + 4.0 * M_PI, 0.5);
    EXPECT_NE(r->output.find("path        cross-track max"), std::string::npos);
  }
  EXPECT_EQ(ec.summary["trace_sha256"], ec2.summary["trace_sha256"]);
  // The loop really turned: it ends 48 m ahead and 18 m to the left.
  const auto pose = ec.summary["plant"]["pose"];
  EXPECT_NEAR(pose["x_m"].get<double>(), 48.0, 0.5);
  EXPECT_NEAR(pose["y_m"].get<double>(), 18.0, 0.5);
}

TEST(Paths, TurnsOutOfReachAreRefusedBeforeAnythingStarts) {
  TempDir tmp;
  const CliResult uni = run_loop(tmp, "uni", kDefault, {"--driver", "unidirectional"});
  EXPECT_EQ(uni.exit_code, 2) << uni.output;
  EXPECT_NE(uni.output.find("trajectory.segments[1].radius_m = 4: at 1 m/s with the unidirectional driver and 30 kg "
                            "the tightest reachable radius is"),
            std::string::npos)
      << uni.output;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() + "/uni"));
  // The newcomer's first own scenario: an arc of 20 m at 5 m/s, 24 agents, 30 kg.
  const std::string scen = tmp.path() + "/turn24.yaml";
  write_file(scen,
             "name: turn24\nagents: 24\ngross_mass_kg: 30\nduration_s: 30\ntrajectory:\n  segments:\n"
             "    - {type: straight, speed_mps: 5, duration_s: 10}\n"
             "    - {type: arc, speed_mps: 5, radius_m: 20, duration_s: 10}\n"
             "    - {type: straight, speed_mps: 5, duration_s: 10}\n");
  const CliResult arc = run_loop(tmp, "arc", scen);
  EXPECT_EQ(arc.exit_code, 2) << arc.output;
  EXPECT_NE(arc.output.find("turn24.yaml: trajectory.segments[1].radius_m = 20: at 5 m/s with the unidirectional "
                            "driver and 30 kg the tightest reachable radius is"),
            std::string::npos)
      << arc.output;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() + "/arc"));
}

TEST(Paths, AWaypointRouteIsTrackedLikeTheArcsItStandsFor) {
  TempDir tmp;
  const std::string route = tmp.path() + "/route.yaml";
  // The loop as 6 points: the corners rounded with the loop's 4 m, one extra point on the first
  // straight and one on the last. The ramp covers the first 1 m as in the default scenario.
  write_file(route,
             "name: route\nagents: 16\ngross_mass_kg: 30\nmode: all\nduration_s: 67\n"
             "robot: {driver: bidirectional}\ncontrol: {kp: 4, ki: 20}\n"
             "trajectory:\n  accel_mps2: 0.5\n  segments:\n"
             "    - {type: waypoints, speed_mps: 1, corner_radius_m: 4,\n"
             "       points: [[0, 0], [12, 0], [24, 0], [24, 18], [36, 18], [48, 18]]}\n"
             "    - {type: stop, duration_s: 3.5}\n");
  const CliResult pts = run_loop(tmp, "pts", route);
  ASSERT_EQ(pts.exit_code, 0) << pts.output;
  const CliResult arcs = run_loop(tmp, "arcs", kDefault, {"--mode", "all"});
  ASSERT_EQ(arcs.exit_code, 0) << arcs.output;
  for (const char* k : {"cross_track_max_m", "cross_track_rms_m", "heading_error_max_rad"}) {
    const double a = path_figure(arcs, k), b = path_figure(pts, k);
    EXPECT_NEAR(b, a, 0.1 * a) << k;
    std::printf("[ figures  ] %s: arcs %.4f, waypoints %.4f\n", k, a, b);
  }
}

TEST(Paths, KillingThreeOuterAgentsInATurnKeepsThePath) {
  TempDir tmp;
  // The first turn (left) runs from t = 21 s to 27.3 s: the right side is the outer one.
  const CliResult r =
      run_loop(tmp, "kill", kDefault, {"--kill", "R0@24", "--kill", "R1@24", "--kill", "R2@24"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.summary["status"], "ok");
  EXPECT_LE(path_figure(r, "cross_track_max_m"), 0.5);
  EXPECT_EQ(r.summary["plant"]["live_agents"]["R"].get<int>(), 5);
  std::printf("[ figures  ] cross-track max %.4f m at %.2f s, rms %.4f m\n", path_figure(r, "cross_track_max_m"),
              path_figure(r, "cross_track_max_t_s"), path_figure(r, "cross_track_rms_m"));
}

TEST(Paths, TheReachBoundAgainstAFleetJustInsideAndJustOutside) {
  // 13.2 kg with the paper's unidirectional driver at 2 m/s: the bound from model/reach.
  maptr::config::Scenario s;
  const double v = 2.0;
  const double bound = maptr::model::tightest_radius(s.robot, v, maptr::model::battery_voltage(s.robot.battery, 0));
  ASSERT_TRUE(std::isfinite(bound) && bound > 1.0);
  TempDir tmp;
  auto scenario = [&](const std::string& name, double radius) {
    const std::string path = tmp.path() + "/" + name + ".yaml";
    write_file(path, "name: " + name + "\nagents: 16\nmode: all\nduration_s: 40\ncontrol: {kp: 4, ki: 20}\n" +
                         "trajectory:\n  accel_mps2: 1\n  segments:\n    - {type: straight, speed_mps: 2, duration_s: 5}\n" +
                         "    - {type: arc, speed_mps: 2, radius_m: " + std::to_string(radius) +
                         ", duration_s: 35}\n");
    return path;
  };
  const CliResult inside = run_loop(tmp, "inside", scenario("inside", 1.05 * bound));
  ASSERT_EQ(inside.exit_code, 0) << inside.output;
  EXPECT_EQ(inside.summary["status"], "ok");
  EXPECT_LE(path_figure(inside, "cross_track_max_m"), 0.5);
  std::printf("[ figures  ] bound %.2f m; at 1.05 x: cross-track max %.4f m, rms %.4f m\n", bound,
              path_figure(inside, "cross_track_max_m"), path_figure(inside, "cross_track_rms_m"));
  const CliResult outside = run_loop(tmp, "outside", scenario("outside", 0.95 * bound));
  EXPECT_EQ(outside.exit_code, 2) << outside.output;
  EXPECT_NE(outside.output.find("tightest reachable radius is"), std::string::npos) << outside.output;
}

}  // namespace
