// The scenario's fields, declared once: YAML path, type, range, unit and description, and how
// each is read from and written to the struct. Parsing, validation, to_yaml, set_field and the
// error messages all come from these tables.
#include <cmath>
#include <type_traits>
#include <variant>

#include "config/fields.hpp"
#include "model/motor.hpp"

namespace maptr::config::detail {

std::string name_problem(const std::string& n) {
  const bool chars_ok = std::all_of(n.begin(), n.end(), [](char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '.' ||
           ch == '_' || ch == '-';
  });
  if (n.empty() || n.size() > kMaxNameLength || !chars_ok || n[0] == '.')
    return "must be 1 to " + std::to_string(kMaxNameLength) +
           " characters from A-Z a-z 0-9 . _ - not starting with '.'";
  return "";
}

std::string target_problem(const std::string& t) {
  int side = 0, index = 0;
  if (parse_agent_name(t, side, index) || parse_host_name(t, index)) return "";
  return "must be an agent (L0, R3, ...), group-L, group-R, central, plant, discovery or a host (h0, h1, ...)";
}

/// A text field that may also be empty.
std::string empty_only(const std::string& t) {
  return t.empty() ? "" : "must be one of open, short, torque, resistance, stuck, sensor, erratic, liar (or empty)";
}

using S = Scenario;

/// robot.driver: a choice of text kept as DriverParams::bidirectional.
Field<S> driver_field() {
  Field<S> f = text<S>(
      "robot.driver", [](auto& s) -> auto& { return s.name; }, {"unidirectional", "bidirectional"},
      "motor driver: unidirectional (voltage in [0, V_B], no braking: the paper's) or bidirectional "
      "(an H-bridge: [-V_B, V_B], it brakes; docs/MODEL.md \"Driver\")");
  f.get = [](const S& s) -> Value { return std::string(s.robot.driver.name()); };
  f.set = [](S& s, const Value& v) { s.robot.driver.bidirectional = std::get<std::string>(v) == "bidirectional"; };
  return f;
}

/// Top-level fields: the run and the robot's size, mass and motor.
Table<S> run_fields() {
  Table<S> v = {
      text<S>(
          "name", [](auto& s) -> auto& { return s.name; }, {}, "scenario name; names the run folder",
          &name_problem, "A-Z a-z 0-9 . _ - (not first: .), 1 to 64 characters"),
      text<S>(
          "mode", [](auto& s) -> auto& { return s.mode; }, {"all", "ec"},
          "all: every agent drives (the paper's NO); ec: energy-conscious (Levels 2 and 3)"),
      real<S>(
          "duration_s", [](auto& s) -> auto& { return s.duration_s; }, above(0, 1e6), "s",
          "simulated time of the run"),
      real<S>(
          "tick_hz", [](auto& s) -> auto& { return s.tick_hz; }, closed(1, 1e4), "Hz",
          "Level-1 control and plant tick rate"),
      flag<S>(
          "realtime", [](auto& s) -> auto& { return s.realtime; }, "pace ticks to the wall clock"),
      integer<S>(
          "trace_every", [](auto& s) -> auto& { return s.trace_every; }, closed(1, 1e6),
          "write every n-th tick to trace.csv"),
      text<S>(
          "record", [](auto& s) -> auto& { return s.record; }, {"all", "plant", "none"},
          "run.mcap: all (every topic), plant (ticks, fault gates, membership, control, ready) or none"),
      text<S>(
          "record_compression", [](auto& s) -> auto& { return s.record_compression; }, {"none", "lz4", "zstd"},
          "run.mcap's chunk compression: zstd (smallest), lz4 (cheapest) or none; Foxglove and MCAP's readers "
          "read all three"),
      text<S>(
          "tick_filter", [](auto& s) -> auto& { return s.tick_filter; }, {"auto", "true", "false"},
          "true: an agent takes only the ticks it answers or needs (the plant's writer filters them); "
          "false: every tick; auto: true in ec, false in all (every agent answers every tick there)"),
      integer<S>(
          "plant_priority", [](auto& s) -> auto& { return s.plant_priority; }, closed(0, 99),
          "SCHED_FIFO priority of the plant's lock-step thread (integrate and publish; it sleeps while "
          "the answers come), so that the agents it wakes do not preempt it in a publish; 0: normal "
          "scheduling. Needs root or an rtprio limit, else the plant runs normally and says so"),
      real<S>(
          "stop_below_speed_pct", [](auto& s) -> auto& { return s.stop_below_speed_pct; },
          Range{0, 100, false, true, false, 1}, "%",
          "end once the speed stays this far below its reference for 5 s (0: never)"),
      integer<S>(
          "agents", [](auto& s) -> auto& { return s.robot.agents; }, Range{4, 512, false, false, false, 4},
          "number of wheel-motor agents N (N/2 per side, N/4 rows)"),
      real<S>(
          "gross_mass_kg", [](auto& s) -> auto& { return s.robot.gross_mass_kg; }, above(0, 1e4), "kg",
          "payload + chassis + motors + wheels"),
      text<S>(
          "motor", [](auto& s) -> auto& { return s.robot.motor.type; }, {"I", "II"},
          "motor type of the paper's Table 1"),
  };
  v.push_back(driver_field());
  // The motor type selects the whole motor of the paper's Table 1.
  for (auto& f : v)
    if (f.info.path == "motor")
      f.set = [](S& s, const Value& x) { s.robot.motor = model::motor_type(std::get<std::string>(x)); };
  return v;
}

/// robot.* and battery.*: the geometry, friction and battery of model::RobotParams.
Table<S> robot_fields() {
  return {
      real<S>(
          "robot.track_m", [](auto& s) -> auto& { return s.robot.track_m; }, above(0, 100), "m",
          "a: distance between the left and right wheel columns"),
      flag<S>(
          "robot.regeneration", [](auto& s) -> auto& { return s.robot.driver.regeneration; },
          "bidirectional driver only: braking power charges the battery (else the driver dissipates it)"),
      real<S>(
          "robot.charge_limit_A", [](auto& s) -> auto& { return s.robot.driver.charge_limit_A; }, above(0, 1e4),
          "A", "most charging current one side's battery takes with regeneration (the rest is dissipated)"),
      real<S>(
          "robot.row_spacing_m", [](auto& s) -> auto& { return s.robot.row_spacing_m; }, above(0, 100), "m",
          "b: distance between wheel rows"),
      real<S>(
          "robot.wheel_radius_m", [](auto& s) -> auto& { return s.robot.wheel_radius_m; }, above(0, 10), "m",
          "r: wheel radius"),
      real<S>(
          "robot.wheel_mass_kg", [](auto& s) -> auto& { return s.robot.wheel_mass_kg; }, closed(0, 1e3), "kg",
          "m_w: mass of one wheel"),
      real<S>(
          "robot.mu_rolling", [](auto& s) -> auto& { return s.robot.mu_rolling; }, closed(0, 10), "1",
          "mu_s: rolling friction coefficient"),
      real<S>(
          "robot.mu_lateral", [](auto& s) -> auto& { return s.robot.mu_lateral; }, closed(0, 10), "1",
          "mu_l: lateral friction coefficient"),
      real<S>(
          "robot.k_s", [](auto& s) -> auto& { return s.robot.k_s; }, above(0, 1e6), "s/m",
          "friction smoothing constant"),
      real<S>(
          "robot.gravity", [](auto& s) -> auto& { return s.robot.gravity; }, above(0, 100), "m/s^2",
          "gravitational acceleration"),
      real<S>(
          "robot.yaw_inertia_kgm2", [](auto& s) -> auto& { return s.robot.yaw_inertia_kgm2; }, closed(0, 1e6),
          "kg m^2", "I_zz (0: derived from a plate carrying the gross mass)"),
      real<S>(
          "robot.wheel_inertia_kgm2", [](auto& s) -> auto& { return s.robot.wheel_inertia_kgm2; },
          closed(0, 1e3), "kg m^2", "wheel inertia (0: derived, disc m_w r^2 / 2)"),
      real<S>(
          "battery.initial_discharge_mAh", [](auto& s) -> auto& { return s.initial_discharge_mAh; },
          closed(0, 1e7), "mAh", "battery discharge at the start (both groups)"),
      real<S>(
          "battery.capacity_mAh", [](auto& s) -> auto& { return s.robot.battery.capacity_mAh; },
          above(0, 1e7), "mAh", "battery capacity"),
      real<S>(
          "battery.h", [](auto& s) -> auto& { return s.robot.battery.h; }, closed(-1e3, 1e3), "V",
          "h of V_B(d) = h e^{w d} + y e^{z d}"),
      real<S>(
          "battery.w", [](auto& s) -> auto& { return s.robot.battery.w; }, closed(-1, 1), "1/mAh",
          "w of V_B(d)"),
      real<S>(
          "battery.y", [](auto& s) -> auto& { return s.robot.battery.y; }, above(0, 1e3), "V",
          "y of V_B(d): the full-battery voltage term"),
      real<S>(
          "battery.z", [](auto& s) -> auto& { return s.robot.battery.z; }, closed(-1, 1), "1/mAh",
          "z of V_B(d)"),
  };
}

/// The rows a core declares beside its tuning struct (control/tunable.hpp), as fields of the
/// scenario: the struct is a base of the scenario's ControlConfig.
template <class Tuning>
Table<S> tunable_fields(const std::vector<control::Tunable<Tuning>>& rows) {
  Table<S> v;
  for (const auto& t : rows) {
    const Range r{t.bounds.min, t.bounds.max, t.bounds.min_open, t.bounds.max_open, false, 1};
    std::visit(
        [&](auto ref) {
          // Reads through a const scenario only (get); writes through a mutable one (set).
          auto acc = [ref](auto& s) -> auto& {
            return ref(const_cast<Tuning&>(static_cast<const Tuning&>(s.control)));
          };
          using V = std::remove_reference_t<decltype(ref(std::declval<Tuning&>()))>;
          if constexpr (std::is_same_v<V, double>)
            v.push_back(real<S>(t.path, acc, r, t.unit, t.description));
          if constexpr (std::is_same_v<V, int>) v.push_back(integer<S>(t.path, acc, r, t.description));
          if constexpr (std::is_same_v<V, bool>) v.push_back(flag<S>(t.path, acc, t.description));
        },
        t.ref);
  }
  return v;
}

/// control.*: each core's tunables (the agents' PID and safe behaviour, Levels 2 and 3, fault
/// detection, central's path follower), then the run's own judgement of the path and the
/// trajectory's ramp, in to_yaml()'s order.
Table<S> control_fields() {
  Table<S> v;
  for (auto part :
       {tunable_fields(control::agent_tunables()), tunable_fields(control::group_tunables()),
        tunable_fields(control::diagnosis_tunables()), tunable_fields(control::central_tunables())})
    v.insert(v.end(), part.begin(), part.end());
  v.push_back(real<S>(
      "control.path_tolerance_m", [](auto& s) -> auto& { return s.control.path_tolerance_m; }, above(0, 1e6),
      "m",
      "a run whose cross-track error exceeds this after its first second ends degraded "
      "(path not followed)"));
  v.push_back(real<S>(
      "trajectory.accel_mps2", [](auto& s) -> auto& { return s.trajectory.accel_mps2; }, closed(0, 1e3),
      "m/s^2", "ramp limit on the speed reference (0: steps)"));
  return v;
}

/// The scenario's own fields, in the order to_yaml() writes them.
const Table<Scenario>& scenario_table() {
  static const Table<S> t = [] {
    Table<S> v = run_fields();
    for (auto part : {robot_fields(), control_fields()}) v.insert(v.end(), part.begin(), part.end());
    return v;
  }();
  return t;
}

/// A segment as a file gives it: the segment, and an arc's radius if given instead of its yaw rate.

const Table<SegmentInput>& segment_table() {
  using G = SegmentInput;
  static const Table<G> t = [] {
    Table<G> v = {
        text<G>(
            "type", [](auto& g) -> auto& { return g.seg.type; }, {"straight", "arc", "stop", "waypoints"},
            "straight, arc (needs a yaw rate or a radius), stop, or waypoints (a route through points, "
            "read as straights and arcs)"),
        real<G>(
            "speed_mps", [](auto& g) -> auto& { return g.seg.speed_mps; }, closed(0, 1e3), "m/s",
            "body speed reference v_x (no reversing)"),
        real<G>(
            "yaw_rate_rad_s", [](auto& g) -> auto& { return g.seg.yaw_rate_rad_s; }, closed(-1e3, 1e3),
            "rad/s", "yaw rate reference w (positive: left)"),
        real<G>(
            "radius_m", [](auto& g) -> auto& { return g.radius_m; }, Range{-1e6, 1e6, false, false, true, 1},
            "m", "arc only, instead of yaw_rate_rad_s: w = speed_mps / radius_m (negative: right)"),
        real<G>(
            "duration_s", [](auto& g) -> auto& { return g.seg.duration_s; }, above(0, 1e6), "s",
            "how long the segment lasts (waypoints: from the route's length and speed)"),
        real<G>(
            "corner_radius_m", [](auto& g) -> auto& { return g.corner_radius_m; }, above(0, 1e6), "m",
            "waypoints only: radius of the arc that rounds each corner of the route"),
    };
    v[4].set = [](G& g, const Value& x) { g.seg.duration_s = std::get<double>(x), g.has_duration = true; };
    v[5].get = nullptr;
    v[5].info.input_only = true;
    v[2].set = [](G& g, const Value& x) {
      g.seg.yaw_rate_rad_s = std::get<double>(x), g.has_yaw_rate = true;
    };
    v[3].set = [](G& g, const Value& x) { g.radius_m = std::get<double>(x), g.has_radius = true; };
    v[3].get = nullptr;
    v[3].info.input_only = true;
    return v;
  }();
  return t;
}

const Table<FaultSpec>& fault_table() {
  using F = FaultSpec;
  static const Table<F> t = {
      text<F>(
          "target", [](auto& f) -> auto& { return f.target; },
          {"group-L", "group-R", "central", "plant", "discovery"}, "process to act on", &target_problem,
          "an agent of the robot (L0, R3, ...) or a host (h0, h1, ...)"),
      text<F>(
          "action", [](auto& f) -> auto& { return f.action; },
          {"kill", "restart", "pause", "resume", "kill-host", "partition", "heal", "fault", "clear"},
          "what to do to it (pause: SIGSTOP, resume: SIGCONT; kill-host, partition, heal: to a host; "
          "fault, clear: an agent breaks while it runs on, and is mended)"),
      real<F>(
          "at_s", [](auto& f) -> auto& { return f.at_s; }, closed(0, 1e6), "s",
          "simulated time of the action (within the run)"),
      text<F>(
          "mode", [](auto& f) -> auto& { return f.mode; },
          {"open", "short", "torque", "resistance", "stuck", "sensor", "erratic", "liar"},
          "action fault: open, short (winding), torque (weak magnet), resistance, stuck (driver) in the motor; "
          "sensor, erratic, liar in the agent (docs/MODEL.md \"Motor faults\")",
          &empty_only, "or empty (an action other than fault)"),
      real<F>(
          "value", [](auto& f) -> auto& { return f.value; }, Range{-1e6, 1e6, false, false, false, 1}, "1",
          "action fault: torque F in (0, 1], resistance F in [1, 100], stuck V [V], sensor B [rad/s], "
          "erratic S [V]; 0 for open, short and liar"),
  };
  return t;
}

}  // namespace maptr::config::detail
