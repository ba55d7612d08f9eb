#include "deploy/cli/level2_command.hpp"

#include <cmath>

#include <cstdio>
#include <iostream>

#include "control/level2/problem.hpp"
#include "model/motor.hpp"

namespace maptr::deploy::cli {

namespace {

/// The Level-2 problem of one side cruising at v.
control::Level2Problem cruise_problem(const config::Scenario& s, double v, double battery_V) {
  control::Level2Problem p;
  p.robot = s.robot;
  p.live = s.robot.per_side();
  p.v_x = v;
  p.phidot_ref_L = p.phidot_ref_R = v / s.robot.wheel_radius_m;
  p.battery_V = battery_V > 0 ? battery_V : s.robot.battery.y;
  p.horizon = s.control.horizon;
  p.step_s = s.control.horizon_step_s;
  return p;
}

void print_rows(const config::Scenario& s, control::Level2Problem p) {
  const double ph = p.phidot_ref_L;
  std::printf("%4s %10s %10s %9s %9s %12s  %s\n", "N_a", "J (of H)", "V need", "V need/VB", "eta", "P side W",
              "feasible");
  for (int n = 1; n <= p.live; ++n) {
    p.n_other = n;
    const double vn = control::required_voltage(p, n);
    const double i = model::armature_current(s.robot.motor, vn, ph);
    std::printf("%4d %10.4f %10.3f %9.3f %9.4f %12.2f  %s\n", n, control::horizon_efficiency(p, n), vn,
                vn / p.battery_V, model::efficiency(s.robot.motor, vn, ph), n * vn * i,
                control::level2_feasible(p, n) ? "yes" : "no (needs more than V_B)");
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

CLI::App* add_level2_command(CLI::App& app, Level2Args& a) {
  auto* l2c = app.add_subcommand("level2", "the Level-2 problem of one side in steady cruise, for every N_a");
  l2c->add_option("scenario", a.robot.scenario, "scenario YAML (default: deploy/scenarios/default.yaml)");
  l2c->add_option("--agents", a.robot.agents, "number of agents N");
  l2c->add_option("--gross-kg", a.robot.gross_kg, "gross mass, kg");
  l2c->add_option("--motor", a.robot.motor, "motor type I or II");
  l2c->add_option("--speed", a.robot.speed, "cruise speed, m/s (default: the first segment's)");
  l2c->add_option("--battery-v", a.battery_V, "battery voltage, V (default: full, 23.4 V)");
  return l2c;
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
  control::Level2Problem p = cruise_problem(s, v, battery_V);
  std::printf(
      "Level 2, one side in steady cruise: %d agents, %.1f kg, motor %s, %.2f m/s (%.1f rad/s), V_B %.2f V\n",
      s.robot.agents, s.robot.gross_mass_kg, s.robot.motor.type.c_str(), v, p.phidot_ref_L, p.battery_V);
  print_rows(s, p);
  p.n_other = 0;
  const auto c = control::exhaustive_level2(p);
  std::printf("oracle: N_a = %d per side%s\n", c.n_active,
              c.feasible ? "" : " (no N_a can hold the speed: every live agent runs)");
  return 0;
}

}  // namespace maptr::deploy::cli
