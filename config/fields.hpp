#pragma once
// The machinery behind the scenario's field table (config/scenario.hpp): a field of a record
// (its FieldInfo, how to read it from and write it to the record), range checks, messages that
// quote at most kMaxQuotedBytes of a value, and the tables of the scenario, a trajectory
// segment and a fault. Internal to config/.
#include <yaml-cpp/yaml.h>

#include <functional>
#include <string>
#include <variant>
#include <vector>

#include "config/scenario.hpp"

namespace maptr::config::detail {

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

/// A value as to_yaml() writes it: doubles with 17 significant digits (they read back exact).
std::string yaml_scalar(const Value& v);
/// A value as error messages print it (numbers with 6 significant digits).
std::string message_value(const Value& v);
/// At most kMaxQuotedChars bytes of `text` (cut on a UTF-8 boundary, then "…"), control
/// characters shown as '?', so that a message stays one short line.
std::string quoted(const std::string& text);
std::string describe(const YAML::Node& v);

/// Names the source in every error.
struct Context {
  std::string source;
  [[noreturn]] void fail(const std::string& field, const std::string& value, const std::string& why) const {
    throw ScenarioError(source + ": " + quoted(field) + " = " + quoted(value) + ": " + why);
  }
};

std::string join(const std::string& prefix, const std::string& key);
std::string unit_suffix(const FieldInfo& f);
/// "" if v is allowed in f, else why not.
std::string problem(const FieldInfo& f, const Value& v, std::string (*accept)(const std::string&));
/// Converts a YAML value to the field's type, or fails naming the field.
Value convert(const FieldInfo& f, const YAML::Node& n, const std::string& field, const Context& c);

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

// ---- The hosts section (config/hosts_section.cpp), read and written by hand ----

/// hosts: {count, launcher_address, failover, machines: [{address, command}], placement: [...]}.
void read_hosts(const YAML::Node& v, HostsConfig& h, const Context& c);
/// The section into `root` (nothing without hosts).
void write_hosts(const HostsConfig& h, YAML::Node& root);

// ---- The tables ----

inline Range closed(double lo, double hi) { return Range{lo, hi, false, false, false, 1}; }
inline Range above(double lo, double hi) { return Range{lo, hi, true, false, false, 1}; }  ///< (lo, hi]

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

struct SegmentInput {
  Segment seg{"straight", 0.0, 0.0, 60.0};  ///< a file's segment does not move unless told
  double radius_m = 0.0;
  bool has_radius = false;
  bool has_yaw_rate = false;
  bool has_duration = false;
  /// type waypoints: the route's points [m] in the frame of its start (x ahead, y left), and
  /// the radius of the arc that rounds each corner [m].
  std::vector<std::pair<double, double>> points;
  double corner_radius_m = 1.0;
};

std::string name_problem(const std::string& n);
std::string target_problem(const std::string& t);
/// The scenario's own fields, in the order to_yaml() writes them.
const Table<Scenario>& scenario_table();
const Table<SegmentInput>& segment_table();
const Table<FaultSpec>& fault_table();

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

}  // namespace maptr::config::detail
