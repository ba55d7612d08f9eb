#include "config/scenario.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "model/motor.hpp"

namespace maptr::config {
namespace {

/// Reads one YAML map strictly: typed fields, and every key must be known.
class MapReader {
 public:
  MapReader(const YAML::Node& n, std::string path, std::string source)
      : n_(n), path_(std::move(path)), source_(std::move(source)) {
    if (n_ && !n_.IsMap()) fail(path_.empty() ? "(top level)" : path_, describe(n_), "must be a mapping");
  }

  template <class T>
  void get(const std::string& key, T& out) {
    used_.insert(key);
    if (!n_ || !n_[key]) return;
    const YAML::Node v = n_[key];
    try {
      if (!v.IsScalar()) throw YAML::Exception(YAML::Mark(), "not a scalar");
      out = v.as<T>();
    } catch (const YAML::Exception&) {
      fail(field(key), describe(v), std::string("must be ") + type_name<T>());
    }
  }

  YAML::Node child(const std::string& key) {
    used_.insert(key);
    return n_ ? n_[key] : YAML::Node();
  }

  void finish() {
    if (!n_) return;
    for (const auto& kv : n_) {
      const std::string k = kv.first.as<std::string>();
      if (!used_.count(k)) fail(field(k), describe(kv.second), "unknown key");
    }
  }

  std::string field(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  [[noreturn]] void fail(const std::string& f, const std::string& v, const std::string& why) const {
    throw ScenarioError(source_ + ": " + f + " = " + v + ": " + why);
  }

  static std::string describe(const YAML::Node& v) {
    if (!v) return "(missing)";
    if (v.IsScalar()) return v.Scalar();
    YAML::Emitter e;
    e << YAML::Flow << v;
    return e.c_str();
  }

 private:
  template <class T>
  static const char* type_name() {
    if (std::is_same<T, bool>::value) return "true or false";
    if (std::is_integral<T>::value) return "an integer";
    if (std::is_floating_point<T>::value) return "a number";
    return "a string";
  }

  YAML::Node n_;
  std::string path_, source_;
  std::set<std::string> used_;
};

void need(bool ok, const std::string& source, const std::string& field, double value, const std::string& why) {
  if (!ok) {
    std::ostringstream os;
    os << source << ": " << field << " = " << value << ": " << why;
    throw ScenarioError(os.str());
  }
}

}  // namespace

long long Scenario::ticks() const { return std::llround(duration_s * tick_hz); }

void Scenario::validate() const {
  const std::string& src = source.empty() ? std::string("scenario") : source;
  try {
    robot.validate();
    control.pid.validate();
  } catch (const model::ParamError& e) {
    throw ScenarioError(src + ": " + e.what());
  }
  if (mode != "all" && mode != "ec") throw ScenarioError(src + ": mode = " + mode + ": must be all or ec");
  need(std::isfinite(duration_s) && duration_s > 0, src, "duration_s", duration_s, "must be positive");
  need(std::isfinite(tick_hz) && tick_hz >= 1 && tick_hz <= 10000, src, "tick_hz", tick_hz, "must be in [1, 10000]");
  need(trace_every >= 1, src, "trace_every", trace_every, "must be at least 1");
  need(std::isfinite(initial_discharge_mAh) && initial_discharge_mAh >= 0, src, "battery.initial_discharge_mAh",
       initial_discharge_mAh, "must be non-negative");
  need(std::isfinite(stop_below_speed_pct) && stop_below_speed_pct >= 0 && stop_below_speed_pct < 100, src,
       "stop_below_speed_pct", stop_below_speed_pct, "must be in [0, 100)");
  need(control.level2_period_s >= dt(), src, "control.level2_period_s", control.level2_period_s,
       "must be at least one tick");
  need(control.horizon >= 1 && control.horizon <= 1000, src, "control.horizon", control.horizon, "must be in [1, 1000]");
  need(control.horizon_step_s > 0, src, "control.horizon_step_s", control.horizon_step_s, "must be positive");
  need(control.t_on_s > 0, src, "control.t_on_s", control.t_on_s, "must be positive");
  need(control.thermal_limit_s > 0, src, "control.thermal_limit_s", control.thermal_limit_s, "must be positive");
  need(control.group_hold_s >= 0, src, "control.group_hold_s", control.group_hold_s, "must be non-negative");
  need(control.central_timeout_s >= 0, src, "control.central_timeout_s", control.central_timeout_s, "must be non-negative");
  need(control.stop_decel_mps2 > 0, src, "control.stop_decel_mps2", control.stop_decel_mps2, "must be positive");
  if (trajectory.segments.empty()) throw ScenarioError(src + ": trajectory.segments = []: trajectory is empty");
  need(trajectory.accel_mps2 >= 0, src, "trajectory.accel_mps2", trajectory.accel_mps2, "must be non-negative");
  // Wheel speed the motors can reach: no-load speed at the full battery voltage.
  const double v_max = model::no_load_speed(robot.motor, std::min(robot.battery.y, robot.motor.rated_voltage_V)) *
                       robot.wheel_radius_m;
  for (std::size_t i = 0; i < trajectory.segments.size(); ++i) {
    const Segment& s = trajectory.segments[i];
    const std::string f = "trajectory.segments[" + std::to_string(i) + "]";
    if (s.type != "straight" && s.type != "arc" && s.type != "stop")
      throw ScenarioError(src + ": " + f + ".type = " + s.type + ": must be straight, arc or stop");
    need(std::isfinite(s.duration_s) && s.duration_s > 0, src, f + ".duration_s", s.duration_s, "must be positive");
    need(std::isfinite(s.speed_mps), src, f + ".speed_mps", s.speed_mps, "must be finite");
    const double wheel = std::fabs(s.speed_mps) + 0.5 * robot.track_m * std::fabs(s.yaw_rate_rad_s);
    std::ostringstream why;
    why << "needs a wheel speed of " << wheel << " m/s; the motors reach at most " << v_max
        << " m/s (no-load speed at the battery voltage)";
    need(wheel < v_max, src, f + ".speed_mps", s.speed_mps, why.str());
    need(s.speed_mps >= 0, src, f + ".speed_mps", s.speed_mps, "must be non-negative (no reversing modelled)");
  }
  for (std::size_t i = 0; i < faults.size(); ++i) {
    const FaultSpec& f = faults[i];
    const std::string fld = "faults[" + std::to_string(i) + "]";
    int side = 0, idx = 0;
    const bool agent = parse_agent_name(f.target, side, idx);
    if (agent && idx >= robot.per_side())
      throw ScenarioError(src + ": " + fld + ".target = " + f.target + ": no such agent (" +
                          std::to_string(robot.per_side()) + " per side)");
    if (!agent && f.target != "group-L" && f.target != "group-R" && f.target != "central" && f.target != "plant" &&
        f.target != "discovery")
      throw ScenarioError(src + ": " + fld + ".target = " + f.target +
                          ": must be an agent (L0, R3, ...), group-L, group-R, central, plant or discovery");
    if (f.action != "kill" && f.action != "restart")
      throw ScenarioError(src + ": " + fld + ".action = " + f.action + ": must be kill or restart");
    need(f.at_s >= 0 && f.at_s <= duration_s, src, fld + ".at_s", f.at_s, "must be within [0, duration_s]");
  }
}

Scenario parse_scenario(const std::string& text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ScenarioError(source + ": not valid YAML: " + e.what());
  }
  Scenario s;
  s.source = source;
  if (!root || root.IsNull()) {
    s.validate();
    return s;
  }
  MapReader top(root, "", source);
  top.get("name", s.name);
  top.get("mode", s.mode);
  top.get("duration_s", s.duration_s);
  top.get("tick_hz", s.tick_hz);
  top.get("realtime", s.realtime);
  top.get("trace_every", s.trace_every);
  top.get("stop_below_speed_pct", s.stop_below_speed_pct);
  top.get("agents", s.robot.agents);
  top.get("gross_mass_kg", s.robot.gross_mass_kg);
  std::string motor = s.robot.motor.type;
  top.get("motor", motor);
  try {
    s.robot.motor = model::motor_type(motor);
  } catch (const model::ParamError& e) {
    throw ScenarioError(source + ": " + e.what());
  }
  {
    MapReader r(top.child("robot"), "robot", source);
    r.get("track_m", s.robot.track_m);
    r.get("row_spacing_m", s.robot.row_spacing_m);
    r.get("wheel_radius_m", s.robot.wheel_radius_m);
    r.get("wheel_mass_kg", s.robot.wheel_mass_kg);
    r.get("mu_rolling", s.robot.mu_rolling);
    r.get("mu_lateral", s.robot.mu_lateral);
    r.get("k_s", s.robot.k_s);
    r.get("gravity", s.robot.gravity);
    r.get("yaw_inertia_kgm2", s.robot.yaw_inertia_kgm2);
    r.get("wheel_inertia_kgm2", s.robot.wheel_inertia_kgm2);
    r.finish();
  }
  {
    MapReader b(top.child("battery"), "battery", source);
    b.get("capacity_mAh", s.robot.battery.capacity_mAh);
    b.get("initial_discharge_mAh", s.initial_discharge_mAh);
    b.get("h", s.robot.battery.h);
    b.get("w", s.robot.battery.w);
    b.get("y", s.robot.battery.y);
    b.get("z", s.robot.battery.z);
    b.finish();
  }
  {
    MapReader c(top.child("control"), "control", source);
    c.get("kp", s.control.pid.kp);
    c.get("ki", s.control.pid.ki);
    c.get("kd", s.control.pid.kd);
    c.get("level2_period_s", s.control.level2_period_s);
    c.get("horizon", s.control.horizon);
    c.get("horizon_step_s", s.control.horizon_step_s);
    c.get("t_on_s", s.control.t_on_s);
    c.get("thermal_limit_s", s.control.thermal_limit_s);
    c.get("oracle", s.control.oracle);
    c.get("group_hold_s", s.control.group_hold_s);
    c.get("central_timeout_s", s.control.central_timeout_s);
    c.get("stop_decel_mps2", s.control.stop_decel_mps2);
    c.finish();
  }
  if (YAML::Node t = top.child("trajectory")) {
    MapReader tr(t, "trajectory", source);
    tr.get("accel_mps2", s.trajectory.accel_mps2);
    YAML::Node segs = tr.child("segments");
    tr.finish();
    if (!segs || !segs.IsSequence())
      tr.fail("trajectory.segments", MapReader::describe(segs), "must be a list of segments");
    s.trajectory.segments.clear();
    for (std::size_t i = 0; i < segs.size(); ++i) {
      const std::string path = "trajectory.segments[" + std::to_string(i) + "]";
      MapReader sr(segs[i], path, source);
      Segment seg;
      seg.speed_mps = 0.0;
      sr.get("type", seg.type);
      sr.get("speed_mps", seg.speed_mps);
      sr.get("yaw_rate_rad_s", seg.yaw_rate_rad_s);
      double radius = 0.0;
      sr.get("radius_m", radius);
      sr.get("duration_s", seg.duration_s);
      sr.finish();
      if (radius != 0.0) {
        if (seg.type != "arc") sr.fail(path + ".radius_m", std::to_string(radius), "only an arc has a radius");
        seg.yaw_rate_rad_s = seg.speed_mps / radius;
      }
      if (seg.type == "stop") seg.speed_mps = seg.yaw_rate_rad_s = 0.0;
      s.trajectory.segments.push_back(seg);
    }
  }
  if (YAML::Node f = top.child("faults")) {
    if (!f.IsSequence()) top.fail("faults", MapReader::describe(f), "must be a list");
    for (std::size_t i = 0; i < f.size(); ++i) {
      MapReader fr(f[i], "faults[" + std::to_string(i) + "]", source);
      FaultSpec fs;
      fr.get("target", fs.target);
      fr.get("action", fs.action);
      fr.get("at_s", fs.at_s);
      fr.finish();
      s.faults.push_back(fs);
    }
  }
  top.finish();
  s.validate();
  return s;
}

Scenario load_scenario(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ScenarioError(path + ": cannot open the scenario file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_scenario(ss.str(), path);
}

std::string to_yaml(const Scenario& s) {
  YAML::Emitter e;
  e.SetDoublePrecision(17);
  e << YAML::BeginMap;
  e << YAML::Key << "name" << YAML::Value << s.name;
  e << YAML::Key << "mode" << YAML::Value << s.mode;
  e << YAML::Key << "duration_s" << YAML::Value << s.duration_s;
  e << YAML::Key << "tick_hz" << YAML::Value << s.tick_hz;
  e << YAML::Key << "realtime" << YAML::Value << s.realtime;
  e << YAML::Key << "trace_every" << YAML::Value << s.trace_every;
  e << YAML::Key << "stop_below_speed_pct" << YAML::Value << s.stop_below_speed_pct;
  e << YAML::Key << "agents" << YAML::Value << s.robot.agents;
  e << YAML::Key << "gross_mass_kg" << YAML::Value << s.robot.gross_mass_kg;
  e << YAML::Key << "motor" << YAML::Value << s.robot.motor.type;
  const auto& r = s.robot;
  e << YAML::Key << "robot" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "track_m" << YAML::Value << r.track_m << YAML::Key << "row_spacing_m" << YAML::Value
    << r.row_spacing_m << YAML::Key << "wheel_radius_m" << YAML::Value << r.wheel_radius_m << YAML::Key
    << "wheel_mass_kg" << YAML::Value << r.wheel_mass_kg << YAML::Key << "mu_rolling" << YAML::Value
    << r.mu_rolling << YAML::Key << "mu_lateral" << YAML::Value << r.mu_lateral << YAML::Key << "k_s"
    << YAML::Value << r.k_s << YAML::Key << "gravity" << YAML::Value << r.gravity << YAML::Key
    << "yaw_inertia_kgm2" << YAML::Value << r.yaw_inertia_kgm2 << YAML::Key << "wheel_inertia_kgm2"
    << YAML::Value << r.wheel_inertia_kgm2;
  e << YAML::EndMap;
  e << YAML::Key << "battery" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "initial_discharge_mAh" << YAML::Value << s.initial_discharge_mAh;
  e << YAML::Key << "capacity_mAh" << YAML::Value << r.battery.capacity_mAh << YAML::Key << "h" << YAML::Value
    << r.battery.h << YAML::Key << "w" << YAML::Value << r.battery.w << YAML::Key << "y" << YAML::Value
    << r.battery.y << YAML::Key << "z" << YAML::Value << r.battery.z;
  e << YAML::EndMap;
  const auto& c = s.control;
  e << YAML::Key << "control" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "kp" << YAML::Value << c.pid.kp << YAML::Key << "ki" << YAML::Value << c.pid.ki << YAML::Key
    << "kd" << YAML::Value << c.pid.kd << YAML::Key << "level2_period_s" << YAML::Value << c.level2_period_s
    << YAML::Key << "horizon" << YAML::Value << c.horizon << YAML::Key << "horizon_step_s" << YAML::Value
    << c.horizon_step_s << YAML::Key << "t_on_s" << YAML::Value << c.t_on_s << YAML::Key << "thermal_limit_s"
    << YAML::Value << c.thermal_limit_s << YAML::Key << "oracle" << YAML::Value << c.oracle << YAML::Key
    << "group_hold_s" << YAML::Value << c.group_hold_s << YAML::Key << "central_timeout_s" << YAML::Value
    << c.central_timeout_s << YAML::Key << "stop_decel_mps2" << YAML::Value << c.stop_decel_mps2;
  e << YAML::EndMap;
  e << YAML::Key << "trajectory" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "accel_mps2" << YAML::Value << s.trajectory.accel_mps2;
  e << YAML::Key << "segments" << YAML::Value << YAML::BeginSeq;
  for (const auto& g : s.trajectory.segments) {
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "type" << YAML::Value << g.type << YAML::Key << "speed_mps"
      << YAML::Value << g.speed_mps << YAML::Key << "yaw_rate_rad_s" << YAML::Value << g.yaw_rate_rad_s
      << YAML::Key << "duration_s" << YAML::Value << g.duration_s << YAML::EndMap;
  }
  e << YAML::EndSeq << YAML::EndMap;
  e << YAML::Key << "faults" << YAML::Value << YAML::BeginSeq;
  for (const auto& f : s.faults)
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "target" << YAML::Value << f.target << YAML::Key << "action"
      << YAML::Value << f.action << YAML::Key << "at_s" << YAML::Value << f.at_s << YAML::EndMap;
  e << YAML::EndSeq;
  e << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

std::string agent_name(int side, int index) { return (side == 0 ? "L" : "R") + std::to_string(index); }

bool parse_agent_name(const std::string& n, int& side, int& index) {
  if (n.size() < 2 || (n[0] != 'L' && n[0] != 'R')) return false;
  for (std::size_t i = 1; i < n.size(); ++i)
    if (n[i] < '0' || n[i] > '9') return false;
  if (n.size() > 5) return false;
  side = n[0] == 'L' ? 0 : 1;
  index = std::stoi(n.substr(1));
  return true;
}

}  // namespace maptr::config
