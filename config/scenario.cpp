#include "config/scenario.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <set>
#include <sstream>
#include <variant>

#include "config/fields.hpp"
#include "config/waypoints.hpp"
#include "model/battery.hpp"
#include "model/motor.hpp"
#include "model/reach.hpp"

namespace maptr::config {
namespace {

using namespace detail;
namespace fs = std::filesystem;

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

std::vector<Segment> read_segment(const YAML::Node& n, const std::string& base, const Context& c) {
  SegmentInput g;
  const ListReader<SegmentInput> lists = [&](const std::string& key, const YAML::Node& v, SegmentInput& in) {
    return read_points(key, v, in, base, c);
  };
  read_map<SegmentInput>(n, segment_table(), g, base, "", c, lists);
  if (g.seg.type == "waypoints") return waypoint_segments(g, base, c);
  if (!g.points.empty()) c.fail(base + ".points", "(given)", "only a waypoints segment has points");
  g.seg.origin = base + (g.has_radius ? ".radius_m" : ".yaw_rate_rad_s");
  if (g.has_radius) {
    if (g.seg.type != "arc")
      c.fail(base + ".radius_m", model::param_value(g.radius_m), "only an arc has a radius");
    if (g.has_yaw_rate)
      c.fail(base + ".radius_m", model::param_value(g.radius_m), "give yaw_rate_rad_s or radius_m, not both");
    g.seg.yaw_rate_rad_s = g.seg.speed_mps / g.radius_m;
  }
  if (g.seg.type == "stop") g.seg.speed_mps = g.seg.yaw_rate_rad_s = 0.0;
  return {g.seg};
}

/// The scenario's lists: trajectory.segments and faults; and the hosts section.
bool read_list(const std::string& path, const YAML::Node& v, Scenario& s, const Context& c) {
  if (path == "hosts") {
    read_hosts(v, s.hosts, c);
    return true;
  }
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
    for (auto& g : read_segment(v[i], "trajectory.segments[" + std::to_string(i) + "]", c))
      s.trajectory.segments.push_back(std::move(g));
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
/// forever on some malformed input.) A second document needs a document marker ("---", or
/// "..." before a bare one): without either, the text is not parsed again.
bool has_second_document(const std::string& text) {
  if (text.find("---") == std::string::npos && text.find("...") == std::string::npos) return false;
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

long long Scenario::ticks() const { return std::llround(duration_s * tick_hz); }

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
  write_hosts(s.hosts, root);
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

std::vector<FieldInfo> reference_field_table() {
  std::vector<FieldInfo> out = field_table();
  for (auto& f : host_field_table()) out.push_back(std::move(f));
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

void set_duration(Scenario& s, const std::string& value, const std::string& origin) {
  set_field(s, "duration_s", value, origin);
  // A run longer than the trajectory: its last segment goes on.
  if (!s.trajectory.segments.empty() && s.trajectory.total_duration() < s.duration_s)
    s.trajectory.segments.back().duration_s += s.duration_s - s.trajectory.total_duration();
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

bool is_host_action(const std::string& a) { return a == "kill-host" || a == "partition" || a == "heal"; }



std::string host_name(int index) { return "h" + std::to_string(index); }

bool parse_host_name(const std::string& n, int& index) {
  if (n.size() < 2 || n.size() > 4 || n[0] != 'h') return false;
  for (std::size_t i = 1; i < n.size(); ++i)
    if (n[i] < '0' || n[i] > '9') return false;
  index = std::stoi(n.substr(1));
  return true;
}

}  // namespace maptr::config
