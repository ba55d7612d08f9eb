#include "deploy/cli/level2_command.hpp"

#include <cmath>

#include <cstdio>
#include <iostream>

#include "control/level2/problem.hpp"
#include "model/battery.hpp"
#include "model/kinematics.hpp"
#include "model/motor.hpp"
#include "model/reach.hpp"

namespace maptr::deploy::cli {

namespace {

/// The Level-2 problem of one side holding speed v at yaw rate w (0: cruise).
control::Level2Problem cruise_problem(const config::Scenario& s, double v, double w, double battery_V) {
  control::Level2Problem p;
  p.robot = s.robot;
  p.live = s.robot.per_side();
  p.v_x = v;
  p.w = w;
  const model::WheelRates ref = model::to_wheel_rates({v, w}, s.robot.track_m, s.robot.wheel_radius_m);
  p.phidot_ref_L = ref.phidot_L;
  p.phidot_ref_R = ref.phidot_R;
  p.battery_V = battery_V > 0 ? battery_V : s.robot.battery.y;
  p.horizon = s.control.horizon;
  p.step_s = s.control.horizon_step_s;
  return p;
}

void print_rows(const config::Scenario& s, control::Level2Problem p) {
  const double ph = p.side == 0 ? p.phidot_ref_L : p.phidot_ref_R;
  std::printf("%4s %10s %10s %9s %9s %12s  %s\n", "N_a", "J (of H)", "V need", "V need/VB", "eta", "P side W",
              "feasible");
  for (int n = 1; n <= p.live; ++n) {
    p.n_other = n;
    const double vn = control::required_voltage(p, n);
    const double i = model::armature_current(s.robot.motor, s.robot.driver, vn, ph);
    std::printf("%4d %10.4f %10.3f %9.3f %9.4f %12.2f  %s\n", n, control::horizon_efficiency(p, n), vn,
                vn / p.battery_V, model::efficiency(s.robot.motor, s.robot.driver, vn, ph), n * vn * i,
                control::level2_feasible(p, n) ? "yes"
                : vn > p.battery_V             ? "no (needs more than V_B)"
                                               : "no (needs a voltage below what the driver applies)");
  }
}

/// --battery-v: a finite voltage above 0 and at most kMaxBatteryV, else a ScenarioError naming it.
double battery_voltage(const std::string& text) {
  constexpr double kMaxBatteryV = 1000.0;
  double v = 0.0;
  std::size_t used = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(v) || v <= 0.0 || v > kMaxBatteryV)
    throw config::ScenarioError("--battery-v = " + text.substr(0, 80) + ": must be a number in (0, 1000] V");
  return v;
}

}  // namespace

namespace {
/// The options of the steady-state tables: the scenario, the robot's overrides and the battery.
CLI::App* robot_table_command(CLI::App& app, const char* name, const char* what, RunArgs& robot,
                              std::string& battery_V) {
  auto* c = app.add_subcommand(name, what);
  c->add_option("scenario", robot.scenario, "scenario YAML (default: deploy/scenarios/default.yaml)");
  c->add_option("--agents", robot.agents, "number of agents N");
  c->add_option("--gross-kg", robot.gross_kg, "gross mass, kg");
  c->add_option("--motor", robot.motor, "motor type I or II");
  c->add_option("--driver", robot.driver, "unidirectional or bidirectional (default: the scenario's)");
  c->add_option("--battery-v", battery_V, "battery voltage, V (default: full, 23.4 V)");
  return c;
}
}  // namespace

CLI::App* add_level2_command(CLI::App& app, Level2Args& a) {
  auto* l2c = robot_table_command(app, "level2", "the Level-2 problem of one side in steady cruise, for every N_a",
                                  a.robot, a.battery_V);
  l2c->add_option("--speed", a.robot.speed, "cruise speed, m/s (default: the first segment's)");
  l2c->add_option("--radius", a.radius_m, "a steady turn of this radius, m (> 0 left, < 0 right; default straight)");
  return l2c;
}

CLI::App* add_reach_command(CLI::App& app, ReachArgs& a) {
  auto* rc = robot_table_command(app, "reach", "the tightest radius the robot holds in a steady turn, against speed",
                                 a.robot, a.battery_V);
  rc->add_option("--max-speed", a.max_speed_mps, "highest speed of the table, m/s (default: the motors' reach)")
      ->check(CLI::Range(0.01, 1000.0));
  return rc;
}

int cmd_reach(const ReachArgs& a) {
  config::Scenario s;
  double battery_V = 0.0;
  try {
    s = scenario_from(a.robot);
    s.trajectory.segments = {config::Segment{"straight", 1.0, 0.0, s.duration_s, ""}};
    s.validate();
    battery_V = a.battery_V.empty() ? model::battery_voltage(s.robot.battery, s.initial_discharge_mAh)
                                    : battery_voltage(a.battery_V);
  } catch (const std::exception& e) {
    std::cerr << "maptr: " << e.what() << "\n";
    return 2;
  }
  const auto& r = s.robot;
  const double top = a.max_speed_mps > 0.0 ? a.max_speed_mps
                                           : 0.95 * model::no_load_speed(r.motor, battery_V) * r.wheel_radius_m;
  std::printf("Reach: %d agents, %.1f kg, motor %s, %s driver, V_B %.2f V (steady turns at %.0f %% of V_B)\n",
              r.agents, r.gross_mass_kg, r.motor.type.c_str(), r.driver.name(), battery_V,
              100.0 * model::kReachVoltageShare);
  std::printf("%10s %18s %14s\n", "speed m/s", "tightest radius m", "yaw rate rad/s");
  for (int i = 1; i <= 12; ++i) {
    const double v = top * i / 12.0;
    const double rmin = model::tightest_radius(r, v, battery_V);
    if (std::isinf(rmin))
      std::printf("%10.3f %18s %14s\n", v, "none", "-");
    else if (rmin == 0.0)
      std::printf("%10.3f %18s %14s\n", v, "any", "-");
    else
      std::printf("%10.3f %18.3f %14.4f\n", v, rmin, v / rmin);
  }
  return 0;
}

int cmd_level2(const Level2Args& a) {
  config::Scenario s;
  double battery_V = 0.0;  // 0: the scenario's full battery
  try {
    s = scenario_from(a.robot);
    s.validate();
    if (!a.battery_V.empty()) battery_V = battery_voltage(a.battery_V);
  } catch (const std::exception& e) {
    std::cerr << "maptr: " << e.what() << "\n";
    return 2;
  }
  const double v = s.trajectory.segments.front().speed_mps;
  const double w = a.radius_m != 0.0 ? v / a.radius_m : 0.0;
  control::Level2Problem p = cruise_problem(s, v, w, battery_V);
  if (w == 0.0)
    std::printf("Level 2, one side in steady cruise: %d agents, %.1f kg, motor %s, %s driver, %.2f m/s (%.1f rad/s), "
                "V_B %.2f V\n",
                s.robot.agents, s.robot.gross_mass_kg, s.robot.motor.type.c_str(), s.robot.driver.name(), v,
                p.phidot_ref_L, p.battery_V);
  else
    std::printf("Level 2 in a steady turn of radius %.2f m: %d agents, %.1f kg, motor %s, %s driver, %.2f m/s, "
                "%.4f rad/s, V_B %.2f V\n",
                a.radius_m, s.robot.agents, s.robot.gross_mass_kg, s.robot.motor.type.c_str(), s.robot.driver.name(),
                v, w, p.battery_V);
  for (int side = 0; side < (w == 0.0 ? 1 : 2); ++side) {
    p.side = side;
    if (w != 0.0)
      std::printf("side %s (wheel speed %.2f rad/s%s):\n", side == 0 ? "L" : "R",
                  side == 0 ? p.phidot_ref_L : p.phidot_ref_R,
                  control::required_voltage(p, 1) < 0.0 ? ", a braking demand" : "");
    print_rows(s, p);
    p.n_other = 0;
    const auto c = control::exhaustive_level2(p);
    std::printf("oracle: N_a = %d%s%s\n", c.n_active, w == 0.0 ? " per side" : "",
                c.feasible ? "" : " (no N_a can hold the speed: every live agent runs)");
  }
  return 0;
}

}  // namespace maptr::deploy::cli
