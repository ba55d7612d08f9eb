#include "config/scenario.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <variant>

#include "model/motor.hpp"

namespace maptr::config {
namespace {

namespace fs = std::filesystem;

using Value = std::variant<bool, long long, double, std::string>;

/// A field of a record R: what field_table() shows, and how to read and write it in R.
template <class R>
struct Field {
  FieldInfo info;                                       ///< path relative to R
  std::string (*accept)(const std::string&) = nullptr;  ///< text: "" if acceptable beyond choices
  std::function<Value(const R&)> get;                   ///< empty: input only
  std::function<void(R&, const Value&)> set;
};

template <class R>
using Table = std::vector<Field<R>>;

// ---- Value formatting ----

/// A value as to_yaml() writes it: doubles with 17 significant digits (they read back exact).
std::string yaml_scalar(const Value& v) {
  if (const double* d = std::get_if<double>(&v)) {
    if (std::isnan(*d)) return ".nan";
    if (std::isinf(*d)) return *d > 0 ? ".inf" : "-.inf";
    std::ostringstream os;
    os.precision(17);
    os << *d;
    return os.str();
  }
  if (const long long* i = std::get_if<long long>(&v)) return std::to_string(*i);
  if (const bool* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
  return std::get<std::string>(v);
}

/// A value as error messages print it (numbers with 6 significant digits).
std::string message_value(const Value& v) {
  if (const double* d = std::get_if<double>(&v)) return model::param_value(*d);
  return yaml_scalar(v);
}

/// At most kMaxQuotedChars bytes of `text` (cut on a UTF-8 boundary, then "…"), control
/// characters shown as '?', so that a message stays one short line.
std::string quoted(const std::string& text) {
  std::size_t n = std::min(text.size(), kMaxQuotedChars);
  if (n < text.size())
    while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;
  std::string out = text.substr(0, n);
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = '?';
  return n < text.size() ? out + "…" : out;
}

std::string describe(const YAML::Node& v) {
  if (!v) return "(missing)";
  switch (v.Type()) {
    case YAML::NodeType::Scalar:
      return v.Scalar();
    case YAML::NodeType::Sequence:
      return v.size() == 0 ? "[]" : "(a list of " + std::to_string(v.size()) + ")";
    case YAML::NodeType::Map:
      return v.size() == 0 ? "{}" : "(a mapping)";
    default:
      return "~";
  }
}

/// Names the source in every error.
struct Context {
  std::string source;
  [[noreturn]] void fail(const std::string& field, const std::string& value, const std::string& why) const {
    throw ScenarioError(source + ": " + quoted(field) + " = " + quoted(value) + ": " + why);
  }
};

std::string join(const std::string& prefix, const std::string& key) {
  return prefix.empty() ? key : prefix + "." + key;
}

// ---- Range and checks ----

std::string unit_suffix(const FieldInfo& f) { return f.unit.empty() || f.unit == "1" ? "" : " " + f.unit; }

/// "" if v is allowed in f, else why not.
std::string problem(const FieldInfo& f, const Value& v, std::string (*accept)(const std::string&)) {
  if (f.type == FieldType::kReal || f.type == FieldType::kInteger) {
    const double x =
        f.type == FieldType::kReal ? std::get<double>(v) : static_cast<double>(std::get<long long>(v));
    const std::string in = f.range.describe() + unit_suffix(f);
    if (!std::isfinite(x)) return "must be a finite number in " + in;
    if (!f.range.contains(x)) {
      std::string why = "must be in " + in;
      if (f.range.nonzero) why += ", not zero";
      if (f.range.multiple_of > 1) why += ", a multiple of " + std::to_string(f.range.multiple_of);
      return why;
    }
    return "";
  }
  if (f.type != FieldType::kText) return "";
  const std::string& s = std::get<std::string>(v);
  if (std::find(f.choices.begin(), f.choices.end(), s) != f.choices.end()) return "";
  if (accept) return accept(s);
  std::string list;
  for (const auto& c : f.choices) list += (list.empty() ? "" : ", ") + c;
  return "must be one of " + list;
}

/// Converts a YAML value to the field's type, or fails naming the field.
Value convert(const FieldInfo& f, const YAML::Node& n, const std::string& field, const Context& c) {
  static const char* kTypeWords[] = {"a number", "an integer", "true or false", "a string"};
  const char* want = kTypeWords[static_cast<int>(f.type)];
  if (!n.IsScalar()) c.fail(field, describe(n), std::string("must be ") + want);
  try {
    switch (f.type) {
      case FieldType::kReal:
        return n.as<double>();
      case FieldType::kInteger:
        return n.as<long long>();
      case FieldType::kBool:
        return n.as<bool>();
      case FieldType::kText:
        return n.Scalar();
    }
  } catch (const std::exception&) {
  }
  c.fail(field, n.Scalar(), std::string("must be ") + want);
}

template <class R>
void read_value(const Field<R>& f, const YAML::Node& n, R& rec, const std::string& field, const Context& c) {
  const Value v = convert(f.info, n, field, c);
  const std::string why = problem(f.info, v, f.accept);
  if (!why.empty()) c.fail(field, n.Scalar(), why);
  try {
    f.set(rec, v);
  } catch (const std::exception& e) {
    c.fail(field, n.Scalar(), e.what());
  }
}

template <class R>
void check_record(const Table<R>& t, const R& rec, const std::string& base, const Context& c) {
  for (const auto& f : t) {
    if (!f.get) continue;
    const Value v = f.get(rec);
    const std::string why = problem(f.info, v, f.accept);
    if (!why.empty()) c.fail(join(base, f.info.path), message_value(v), why);
  }
}

// ---- The tables ----

Range closed(double lo, double hi) { return Range{lo, hi, false, false, false, 1}; }
Range above(double lo, double hi) { return Range{lo, hi, true, false, false, 1}; }  ///< (lo, hi]

template <class R, class Acc>
Field<R> real(const char* path, Acc acc, Range r, const char* unit, const char* desc) {
  Field<R> f;
  f.info = FieldInfo{path, FieldType::kReal, r, {}, "", unit, desc, "", false};
  f.get = [acc](const R& x) -> Value { return static_cast<double>(acc(x)); };
  f.set = [acc](R& x, const Value& v) { acc(x) = std::get<double>(v); };
  return f;
}

template <class R, class Acc>
Field<R> integer(const char* path, Acc acc, Range r, const char* desc) {
  Field<R> f;
  f.info = FieldInfo{path, FieldType::kInteger, r, {}, "", "1", desc, "", false};
  f.get = [acc](const R& x) -> Value { return static_cast<long long>(acc(x)); };
  f.set = [acc](R& x, const Value& v) { acc(x) = static_cast<int>(std::get<long long>(v)); };
  return f;
}

template <class R, class Acc>
Field<R> flag(const char* path, Acc acc, const char* desc) {
  Field<R> f;
  f.info = FieldInfo{path, FieldType::kBool, {}, {}, "", "", desc, "", false};
  f.get = [acc](const R& x) -> Value { return static_cast<bool>(acc(x)); };
  f.set = [acc](R& x, const Value& v) { acc(x) = std::get<bool>(v); };
  return f;
}

template <class R, class Acc>
Field<R> text(const char* path, Acc acc, std::vector<std::string> choices, const char* desc,
              std::string (*accept)(const std::string&) = nullptr, const char* rule = "") {
  Field<R> f;
  f.info = FieldInfo{path, FieldType::kText, {}, std::move(choices), rule, "", desc, "", false};
  f.accept = accept;
  f.get = [acc](const R& x) -> Value { return std::string(acc(x)); };
  f.set = [acc](R& x, const Value& v) { acc(x) = std::get<std::string>(v); };
  return f;
}

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
  if (parse_agent_name(t, side, index)) return "";
  return "must be an agent (L0, R3, ...), group-L, group-R, central, plant or discovery";
}

using S = Scenario;

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

/// control.* and trajectory.accel_mps2.
Table<S> control_fields() {
  return {
      real<S>(
          "control.kp", [](auto& s) -> auto& { return s.control.pid.kp; }, closed(0, 1e6), "V s/rad",
          "wheel PID proportional gain (kp and ki not both zero)"),
      real<S>(
          "control.ki", [](auto& s) -> auto& { return s.control.pid.ki; }, closed(0, 1e6), "V/rad",
          "wheel PID integral gain"),
      real<S>(
          "control.kd", [](auto& s) -> auto& { return s.control.pid.kd; }, closed(0, 1e6), "V s^2/rad",
          "wheel PID derivative gain"),
      real<S>(
          "control.level2_period_s", [](auto& s) -> auto& { return s.control.level2_period_s; },
          above(0, 1e6), "s", "Level-2 decision period (at least one tick)"),
      integer<S>(
          "control.horizon", [](auto& s) -> auto& { return s.control.horizon; }, closed(1, 1000),
          "Level-2 horizon, steps"),
      real<S>(
          "control.horizon_step_s", [](auto& s) -> auto& { return s.control.horizon_step_s; }, above(0, 1e3),
          "s", "Level-2 horizon step"),
      real<S>(
          "control.t_on_s", [](auto& s) -> auto& { return s.control.t_on_s; }, above(0, 1e7), "s",
          "Level-3 period T_ON"),
      real<S>(
          "control.thermal_limit_s", [](auto& s) -> auto& { return s.control.thermal_limit_s; },
          above(0, 1e7), "s", "longest continuous active time of an agent"),
      flag<S>(
          "control.oracle", [](auto& s) -> auto& { return s.control.oracle; },
          "also run the exhaustive Level-2 search and report it"),
      real<S>(
          "control.group_hold_s", [](auto& s) -> auto& { return s.control.group_hold_s; }, closed(0, 1e6),
          "s", "agents hold the last assignment this long without their group"),
      real<S>(
          "control.central_timeout_s", [](auto& s) -> auto& { return s.control.central_timeout_s; },
          closed(0, 1e6), "s", "agents ramp to a stop after this long without central"),
      real<S>(
          "control.stop_decel_mps2", [](auto& s) -> auto& { return s.control.stop_decel_mps2; },
          above(0, 1e3), "m/s^2", "deceleration of that ramp"),
      real<S>(
          "trajectory.accel_mps2", [](auto& s) -> auto& { return s.trajectory.accel_mps2; }, closed(0, 1e3),
          "m/s^2", "ramp limit on the speed reference (0: steps)"),
  };
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
struct SegmentInput {
  Segment seg{"straight", 0.0, 0.0, 60.0};  ///< a file's segment does not move unless told
  double radius_m = 0.0;
  bool has_radius = false;
  bool has_yaw_rate = false;
};

const Table<SegmentInput>& segment_table() {
  using G = SegmentInput;
  static const Table<G> t = [] {
    Table<G> v = {
        text<G>(
            "type", [](auto& g) -> auto& { return g.seg.type; }, {"straight", "arc", "stop"},
            "straight, arc (needs a yaw rate or a radius) or stop"),
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
            "how long the segment lasts"),
    };
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
          "an agent of the robot (L0, R3, ...)"),
      text<F>(
          "action", [](auto& f) -> auto& { return f.action; }, {"kill", "restart"}, "what to do to it"),
      real<F>(
          "at_s", [](auto& f) -> auto& { return f.at_s; }, closed(0, 1e6), "s",
          "simulated time of the action (within the run)"),
  };
  return t;
}

template <class R>
const Field<R>* find(const Table<R>& t, const std::string& path) {
  for (const auto& f : t)
    if (f.info.path == path) return &f;
  return nullptr;
}

template <class R>
bool is_section(const Table<R>& t, const std::string& path) {
  for (const auto& f : t)
    if (f.info.path.compare(0, path.size() + 1, path + ".") == 0) return true;
  return false;
}

// ---- Reading ----

/// Handles the keys of a record that are lists (returns false for a key it does not know).
template <class R>
using ListReader = std::function<bool(const std::string& path, const YAML::Node& value, R& rec)>;

/// Reads a mapping into rec: every key known, none twice, each value typed and in range.
/// `section` is the table prefix ("" or "robot"), `base` what messages put before it.
template <class R>
void read_map(const YAML::Node& n, const Table<R>& t, R& rec, const std::string& base,
              const std::string& section, const Context& c, const ListReader<R>& lists) {
  const std::string here = join(base, section);
  if (!n.IsMap()) c.fail(here.empty() ? "(top level)" : here, describe(n), "must be a mapping");
  std::set<std::string> seen;
  for (auto it = n.begin(); it != n.end(); ++it) {
    if (!it->first.IsScalar())
      c.fail(join(here, describe(it->first)), describe(it->second), "a key must be a name");
    const std::string key = it->first.Scalar();
    const std::string path = join(section, key), field = join(base, path);
    if (!seen.insert(key).second) c.fail(field, describe(it->second), "duplicate key (given more than once)");
    if (const Field<R>* f = find(t, path))
      read_value(*f, it->second, rec, field, c);
    else if (lists && lists(path, it->second, rec))
      continue;
    else if (is_section(t, path))
      read_map(it->second, t, rec, base, path, c, lists);
    else
      c.fail(field, describe(it->second), "unknown key");
  }
}

Segment read_segment(const YAML::Node& n, const std::string& base, const Context& c) {
  SegmentInput g;
  read_map<SegmentInput>(n, segment_table(), g, base, "", c, nullptr);
  if (g.has_radius) {
    if (g.seg.type != "arc")
      c.fail(base + ".radius_m", model::param_value(g.radius_m), "only an arc has a radius");
    if (g.has_yaw_rate)
      c.fail(base + ".radius_m", model::param_value(g.radius_m), "give yaw_rate_rad_s or radius_m, not both");
    g.seg.yaw_rate_rad_s = g.seg.speed_mps / g.radius_m;
  }
  if (g.seg.type == "stop") g.seg.speed_mps = g.seg.yaw_rate_rad_s = 0.0;
  return g.seg;
}

/// The scenario's lists: trajectory.segments and faults.
bool read_list(const std::string& path, const YAML::Node& v, Scenario& s, const Context& c) {
  if (path != "trajectory.segments" && path != "faults") return false;
  if (!v.IsSequence()) c.fail(path, describe(v), "must be a list");
  if (path == "faults") {
    s.faults.clear();
    for (std::size_t i = 0; i < v.size(); ++i) {
      FaultSpec f;
      read_map<FaultSpec>(v[i], fault_table(), f, "faults[" + std::to_string(i) + "]", "", c, nullptr);
      s.faults.push_back(f);
    }
    return true;
  }
  s.trajectory.segments.clear();
  for (std::size_t i = 0; i < v.size(); ++i)
    s.trajectory.segments.push_back(read_segment(v[i], "trajectory.segments[" + std::to_string(i) + "]", c));
  return true;
}

/// Ignores every parse event: only whether a document follows matters.
class SkipEvents : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
  }
  void OnMapEnd() override {}
};

/// True if the text holds a second document. (Reads at most two: yaml-cpp's LoadAll can loop
/// forever on some malformed input.)
bool has_second_document(const std::string& text) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  SkipEvents skip;
  return parser.HandleNextDocument(skip) && parser.HandleNextDocument(skip);
}

/// The one document of the text, or a ScenarioError.
YAML::Node load_document(const std::string& text, const Context& c) {
  if (text.size() > kMaxScenarioBytes)
    c.fail("(file)", std::to_string(text.size()) + " bytes",
           "a scenario is at most " + std::to_string(kMaxScenarioBytes) + " bytes");
  YAML::Node doc;
  try {
    doc = YAML::Load(text);
    if (doc && !doc.IsNull() && has_second_document(text))
      c.fail("(top level)", "a second document", "must be one document");
  } catch (const YAML::Exception& e) {
    c.fail("(document)",
           "line " + std::to_string(e.mark.line + 1) + ", column " + std::to_string(e.mark.column + 1),
           "not valid YAML: " + quoted(e.msg));
  }
  if (!doc || doc.IsNull())
    c.fail("(top level)", "(empty)", "the file holds no scenario (empty or only comments)");
  return doc;
}

// ---- Validation of the rules that tie fields together ----

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

void check_faults(const Scenario& s, const Context& c) {
  for (std::size_t i = 0; i < s.faults.size(); ++i) {
    const FaultSpec& f = s.faults[i];
    const std::string base = "faults[" + std::to_string(i) + "]";
    check_record(fault_table(), f, base, c);
    int side = 0, idx = 0;
    if (parse_agent_name(f.target, side, idx) && idx >= s.robot.per_side())
      c.fail(base + ".target", f.target,
             "no such agent (" + std::to_string(s.robot.per_side()) + " per side)");
    if (f.at_s > s.duration_s)
      c.fail(base + ".at_s", model::param_value(f.at_s), "must be within [0, duration_s]");
  }
}

template <class R>
void add_infos(std::vector<FieldInfo>& out, const Table<R>& t, const R& defaults, const std::string& prefix) {
  for (const auto& f : t) {
    FieldInfo i = f.info;
    i.path = prefix + i.path;
    if (f.get) i.default_value = yaml_scalar(f.get(defaults));
    out.push_back(i);
  }
}

}  // namespace

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (min_open ? !(v > min) : !(v >= min)) return false;
  if (max_open ? !(v < max) : !(v <= max)) return false;
  if (nonzero && v == 0.0) return false;
  return multiple_of <= 1 || std::fmod(v, static_cast<double>(multiple_of)) == 0.0;
}

std::string Range::describe() const {
  return (min_open ? "(" : "[") + model::param_value(min) + ", " + model::param_value(max) +
         (max_open ? ")" : "]");
}

long long Scenario::ticks() const { return std::llround(duration_s * tick_hz); }

void Scenario::validate() const {
  const Context c{source.empty() ? std::string("scenario") : source};
  check_record(scenario_table(), *this, "", c);
  try {
    robot.validate();
    control.pid.validate();
  } catch (const model::ParamError& e) {
    throw ScenarioError(c.source + ": " + e.what());
  }
  if (control.level2_period_s < dt())
    c.fail("control.level2_period_s", model::param_value(control.level2_period_s),
           "must be at least one tick");
  check_segments(*this, c);
  check_faults(*this, c);
}

Scenario parse_scenario(const std::string& text, const std::string& source) {
  const Context c{source};
  Scenario s;
  s.source = source;
  try {
    const YAML::Node root = load_document(text, c);
    const ListReader<Scenario> lists = [&c](const std::string& p, const YAML::Node& v, Scenario& sc) {
      return read_list(p, v, sc, c);
    };
    read_map<Scenario>(root, scenario_table(), s, "", "", c, lists);
    const YAML::Node& croot = root;
    if (croot["trajectory"] && !croot["trajectory"]["segments"])
      c.fail("trajectory.segments", "(missing)", "a trajectory needs its list of segments");
  } catch (const ScenarioError&) {
    throw;
  } catch (const std::exception& e) {
    throw ScenarioError(source + ": " + quoted(e.what()));
  }
  s.validate();
  return s;
}

Scenario load_scenario(const std::string& path) {
  const Context c{path};
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) c.fail("(file)", path, "cannot open the scenario file (no such file)");
  if (!fs::is_regular_file(st))
    c.fail("(file)", path, "is not a regular file (a directory, a device or a pipe?)");
  const auto size = fs::file_size(path, ec);
  if (!ec && size > kMaxScenarioBytes)
    c.fail("(file)", std::to_string(size) + " bytes",
           "a scenario is at most " + std::to_string(kMaxScenarioBytes) + " bytes");
  std::ifstream in(path, std::ios::binary);
  if (!in) c.fail("(file)", path, "cannot open the scenario file");
  std::string text(kMaxScenarioBytes + 1, '\0');
  in.read(&text[0], static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  return parse_scenario(text, path);
}

std::string to_yaml(const Scenario& s) {
  YAML::Node root;
  for (const auto& f : scenario_table()) {
    const std::string& p = f.info.path;
    const auto dot = p.find('.');
    if (dot == std::string::npos)
      root[p] = yaml_scalar(f.get(s));
    else
      root[p.substr(0, dot)][p.substr(dot + 1)] = yaml_scalar(f.get(s));
  }
  YAML::Node segs(YAML::NodeType::Sequence);
  for (const auto& g : s.trajectory.segments) {
    YAML::Node m;
    SegmentInput in;
    in.seg = g;
    for (const auto& f : segment_table())
      if (f.get) m[f.info.path] = yaml_scalar(f.get(in));
    m.SetStyle(YAML::EmitterStyle::Flow);
    segs.push_back(m);
  }
  root["trajectory"]["segments"] = segs;
  YAML::Node faults(YAML::NodeType::Sequence);
  for (const auto& x : s.faults) {
    YAML::Node m;
    for (const auto& f : fault_table()) m[f.info.path] = yaml_scalar(f.get(x));
    m.SetStyle(YAML::EmitterStyle::Flow);
    faults.push_back(m);
  }
  root["faults"] = faults;
  YAML::Emitter e;
  e << root;
  return std::string(e.c_str()) + "\n";
}

std::vector<FieldInfo> field_table() {
  std::vector<FieldInfo> out;
  add_infos(out, scenario_table(), Scenario{}, "");
  add_infos(out, segment_table(), SegmentInput{}, "trajectory.segments[].");
  add_infos(out, fault_table(), FaultSpec{}, "faults[].");
  return out;
}

void set_field(Scenario& s, const std::string& path, const std::string& value, const std::string& origin) {
  const Context c{origin};
  // The robot's top-level keys also by their place in the struct.
  static const std::pair<const char*, const char*> kStructPaths[] = {
      {"robot.agents", "agents"}, {"robot.gross_mass_kg", "gross_mass_kg"}, {"robot.motor", "motor"}};
  std::string key = path;
  for (const auto& [in_struct, in_file] : kStructPaths)
    if (path == in_struct) key = in_file;
  const Field<Scenario>* f = find(scenario_table(), key);
  if (!f) c.fail(path, value, "not a scenario field");
  read_value(*f, YAML::Node(value), s, key, c);
}

void set_speed(Scenario& s, const std::string& value, const std::string& origin) {
  const Context c{origin};
  const Field<SegmentInput>* f = find(segment_table(), "speed_mps");
  SegmentInput in;
  read_value(*f, YAML::Node(value), in, "trajectory.segments[].speed_mps", c);
  for (auto& g : s.trajectory.segments)
    if (g.type != "stop") g.speed_mps = in.seg.speed_mps;
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
