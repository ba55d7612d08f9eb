// The rules of the agents' own faults (scenario actions fault and clear): which actions they
// are, when they act, and which mode takes which value.
#include <cmath>

#include "config/scenario.hpp"

namespace maptr::config {

bool is_agent_fault_action(const std::string& a) { return a == "fault" || a == "clear"; }

long long first_tick_at(double at_s, double dt_s) {
  auto k = static_cast<long long>(std::ceil(at_s / dt_s));
  while (k > 0 && static_cast<double>(k - 1) * dt_s >= at_s) --k;
  while (static_cast<double>(k) * dt_s < at_s) ++k;
  return k;
}

std::string fault_mode_problem(const FaultSpec& f, const model::RobotParams& robot, std::string& field) {
  field = "mode";
  if (f.action != "fault") {
    if (!f.mode.empty()) return "only an action fault has a mode";
    field = "value";
    return f.value != 0.0 ? "only an action fault has a value" : "";
  }
  if (f.mode.empty())
    return "an action fault needs a mode: open, short, torque, resistance, stuck, sensor, erratic or liar";
  field = "value";
  const double v = f.value, rated = robot.motor.rated_voltage_V;
  if (!std::isfinite(v)) return "must be a finite number";
  if (f.mode == "open" || f.mode == "short" || f.mode == "liar")
    return v != 0.0 ? "mode " + f.mode + " takes no value" : "";
  if (f.mode == "torque")
    return v > 0.0 && v <= 1.0 ? "" : "torque=F scales the motor's torque constant: F in (0, 1]";
  if (f.mode == "resistance")
    return v >= 1.0 && v <= 100.0 ? "" : "resistance=F scales the winding's resistance: F in [1, 100]";
  if (f.mode == "stuck") {
    const double lo = robot.driver.bidirectional ? -rated : 0.0;
    return v >= lo && v <= rated ? ""
                                 : "stuck=V is a voltage the " + std::string(robot.driver.name()) +
                                       " driver can apply: V in [" + model::param_value(lo) + ", " +
                                       model::param_value(rated) + "]";
  }
  if (f.mode == "sensor")
    return v != 0.0 && std::fabs(v) <= 1000.0 ? "" : "sensor=B is a speed offset: B nonzero, |B| <= 1000 rad/s";
  if (f.mode == "erratic") return v > 0.0 && v <= 100.0 ? "" : "erratic=S is a noise level: S in (0, 100] V";
  field = "mode";
  return "unknown mode: one of open, short, torque, resistance, stuck, sensor, erratic, liar";
}

}  // namespace maptr::config
