// The rules that tie a scenario's fields together (Scenario::validate): each field's own range is
// the field table's (config/scenario_fields.cpp); here the trajectory against the motors and the
// robot's reach, the driver, and the fault schedule.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <set>
#include <sstream>

#include "config/fields.hpp"
#include "config/scenario.hpp"
#include "model/battery.hpp"
#include "model/motor.hpp"
#include "model/reach.hpp"

namespace maptr::config {
namespace {

using namespace detail;

void check_segments(const Scenario& s, const Context& c) {
  if (s.trajectory.segments.empty()) c.fail("trajectory.segments", "[]", "trajectory is empty");
  // Wheel speed the motors can reach: no-load speed at the full battery voltage.
  const auto& r = s.robot;
  const double v_max =
      model::no_load_speed(r.motor, std::min(r.battery.y, r.motor.rated_voltage_V)) * r.wheel_radius_m;
  for (std::size_t i = 0; i < s.trajectory.segments.size(); ++i) {
    const Segment& g = s.trajectory.segments[i];
    const std::string base = "trajectory.segments[" + std::to_string(i) + "]";
    SegmentInput in;
    in.seg = g;
    check_record(segment_table(), in, base, c);
    if (g.type == "arc" && g.yaw_rate_rad_s == 0.0)
      c.fail(base + ".yaw_rate_rad_s", "0", "an arc needs a non-zero yaw_rate_rad_s or radius_m");
    const double wheel = std::fabs(g.speed_mps) + 0.5 * r.track_m * std::fabs(g.yaw_rate_rad_s);
    if (!(wheel < v_max)) {
      std::ostringstream why;
      why << "needs a wheel speed of " << wheel << " m/s (speed and yaw rate); the motors reach at most "
          << v_max << " m/s (no-load speed at the battery voltage)";
      c.fail(base + ".speed_mps", model::param_value(g.speed_mps), why.str());
    }
  }
}

/// Every turn of the trajectory within what the robot can hold in a steady turn
/// (model/reach.hpp), at the battery's voltage at the start.
void check_reach(const Scenario& s, const Context& c) {
  const auto& r = s.robot;
  const double battery_V = model::battery_voltage(r.battery, s.initial_discharge_mAh);
  for (std::size_t i = 0; i < s.trajectory.segments.size(); ++i) {
    const Segment& g = s.trajectory.segments[i];
    if (!(g.speed_mps > 0.0) || g.yaw_rate_rad_s == 0.0) continue;
    if (model::steady_turn(r, g.speed_mps, g.yaw_rate_rad_s, battery_V).feasible) continue;
    const double tightest = model::tightest_radius(r, g.speed_mps, battery_V);
    std::ostringstream why;
    why << "at " << g.speed_mps << " m/s with the " << r.driver.name() << " driver and " << r.gross_mass_kg
        << " kg the tightest reachable radius is ";
    if (std::isinf(tightest))
      why << "none (not even a straight line is held)";
    else
      why << std::setprecision(3) << tightest << " m";
    why << " (`maptr reach` prints the bound against speed)";
    const std::string field =
        g.origin.empty() ? "trajectory.segments[" + std::to_string(i) + "].yaw_rate_rad_s" : g.origin;
    const bool by_rate = field.size() > 15 && field.compare(field.size() - 15, 15, ".yaw_rate_rad_s") == 0;
    c.fail(field, model::param_value(by_rate ? g.yaw_rate_rad_s : std::fabs(g.speed_mps / g.yaw_rate_rad_s)),
           why.str());
  }
}

void check_driver(const Scenario& s, const Context& c) {
  if (s.robot.driver.regeneration && !s.robot.driver.bidirectional)
    c.fail("robot.regeneration", "true", "only a bidirectional driver (robot.driver) can regenerate");
}

/// Where a fault's messages point: the file's faults[i], or the option it was given as.
struct FaultContext {
  Context c;
  std::string base;
  FaultContext(const Context& file, const FaultSpec& f, std::size_t i)
      : c(f.origin.empty() ? file : Context{f.origin}),
        base(f.origin.empty() ? "faults[" + std::to_string(i) + "]" : "faults[]") {}
  [[noreturn]] void fail(const std::string& field, const std::string& value, const std::string& why) const {
    c.fail(base + "." + field, value, why);
  }
};

/// The plant is never paused (it is the fleet's clock), and the schedule holds no contradiction.
void check_schedule(const Scenario& s, const Context& c) {
  for (std::size_t i = 0; i < s.faults.size(); ++i)
    if ((s.faults[i].action == "pause" || s.faults[i].action == "resume") && s.faults[i].target == "plant")
      FaultContext(c, s.faults[i], i).fail("target", "plant", "the plant cannot be paused: it is the fleet's clock");
  if (const auto p = schedule_problem(s.faults)) {
    const FaultSpec& f = s.faults[p->index];
    FaultContext(c, f, p->index)
        .fail(p->field, p->field == "at_s" ? model::param_value(f.at_s) : p->field == "target" ? f.target : f.action,
              p->why);
  }
}

void check_faults(const Scenario& s, const Context& file) {
  for (std::size_t i = 0; i < s.faults.size(); ++i) {
    const FaultSpec& f = s.faults[i];
    const FaultContext fc(file, f, i);
    check_record(fault_table(), f, fc.base, fc.c);
    int side = 0, idx = 0;
    if (parse_agent_name(f.target, side, idx) && idx >= s.robot.per_side())
      fc.fail("target", f.target, "no such agent (" + std::to_string(s.robot.per_side()) + " per side)");
    int host = 0;
    const bool host_target = parse_host_name(f.target, host);
    if (is_host_action(f.action) != host_target)
      fc.fail("target", f.target,
              is_host_action(f.action) ? "action " + f.action + " needs a host (h0, h1, ...)"
                                       : "action " + f.action + " needs a process, not a host");
    if (host_target && is_host_action(f.action) && !s.hosts.enabled())
      fc.fail("target", f.target, "a host fault needs a fleet on several hosts (--hosts N)");
    if (host_target && s.hosts.enabled() && host >= s.hosts.count)
      fc.fail("target", f.target, "no such host (" + std::to_string(s.hosts.count) + " hosts: h0..)");
    if (s.hosts.ssh && (f.action == "pause" || f.action == "resume"))
      fc.fail("action", f.action,
              "cannot run with hosts.ssh (--ssh): a process started over ssh runs on its machine, and "
              "SIGSTOP would stop its ssh client, not it");
    if (f.at_s > s.duration_s)
      fc.fail("at_s", model::param_value(f.at_s),
              "after the end of the run (duration_s = " + model::param_value(s.duration_s) + " s)");
    if (is_agent_fault_action(f.action) && !parse_agent_name(f.target, side, idx))
      fc.fail("target", f.target, "action " + f.action + " needs an agent (L0, R3, ...): only a wheel's motor or its agent's software fails this way");
    std::string field;
    const std::string why = fault_mode_problem(f, s.robot, field);
    if (!why.empty()) fc.fail(field, field == "mode" ? f.mode : model::param_value(f.value), why);
  }
  check_schedule(s, file);
}

}  // namespace

void Scenario::validate() const {
  const Context c{source.empty() ? std::string("scenario") : source};
  check_record(scenario_table(), *this, "", c);
  check_driver(*this, c);
  if (control.pid.kp + control.pid.ki <= 0.0)
    c.fail("control.ki", model::param_value(control.pid.ki), "control.kp and control.ki cannot both be zero");
  if (control.level2_period_s < dt())
    c.fail("control.level2_period_s", model::param_value(control.level2_period_s),
           "must be at least one tick");
  if (control.fault_persistence_s < dt())
    c.fail("control.fault_persistence_s", model::param_value(control.fault_persistence_s),
           "must be at least one tick");
  if (hosts.ssh && !hosts.enabled())
    c.fail("hosts.ssh", "true", "the ssh rehearsal runs on namespace hosts: give hosts.count (or --hosts N)");
  check_segments(*this, c);
  check_reach(*this, c);
  check_faults(*this, c);
}

}  // namespace maptr::config
