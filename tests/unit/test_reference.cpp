// The references a user reads instead of the source: docs/SCENARIO.md, docs/SUMMARY.md and
// docs/ENVIRONMENT.md are what `maptr fields --markdown` prints, every key of every example
// scenario is in the scenario reference, summary.json's key patterns match the keys a run writes,
// and every environment variable the product names is the table's.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

#include "comm/posix/environment.hpp"
#include "config/scenario.hpp"
#include "deploy/report/reference.hpp"
#include "records/summary_fields.hpp"

namespace {

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

TEST(Reference, TheCommittedScenarioReferenceIsTheFieldTable) {
  const std::string doc = std::string(MAPTR_SOURCE_DIR) + "/docs/SCENARIO.md";
  EXPECT_EQ(read(doc), maptr::deploy::report::scenario_reference("", true))
      << "docs/SCENARIO.md differs from the field table: build/bin/maptr fields --markdown > docs/SCENARIO.md";
}

TEST(Reference, TheCommittedSummaryReferenceIsTheKeyTable) {
  const std::string doc = std::string(MAPTR_SOURCE_DIR) + "/docs/SUMMARY.md";
  EXPECT_EQ(read(doc), maptr::deploy::report::summary_reference("", true))
      << "docs/SUMMARY.md differs from the key table: build/bin/maptr fields --summary --markdown > docs/SUMMARY.md";
}

TEST(Reference, TheCommittedEnvironmentReferenceIsTheTable) {
  const std::string doc = std::string(MAPTR_SOURCE_DIR) + "/docs/ENVIRONMENT.md";
  EXPECT_EQ(read(doc), maptr::deploy::report::environment_reference(true))
      << "docs/ENVIRONMENT.md differs from comm/posix/environment.hpp: "
         "build/bin/maptr fields --environment --markdown > docs/ENVIRONMENT.md";
}

TEST(Reference, EveryEnvironmentVariableIsNamedOnlyInTheTable) {
  // Outside comm/posix/environment.hpp the product names a variable by the table's constant: a string
  // literal MAPTR_... (or one of the other variables the table holds) anywhere else is a second
  // declaration. MAPTR_TICK_WAKE is a DDS filter class, not a variable.
  std::set<std::string> table;
  for (const auto& v : maptr::comm::kEnvironment) table.insert(v.name);
  const std::regex literal("\"(MAPTR_[A-Z0-9_]+|FASTRTPS_[A-Z0-9_]+|XDG_[A-Z_]+)");
  const std::string root = MAPTR_SOURCE_DIR;
  int files = 0;
  std::set<std::string> seen;
  for (auto it = std::filesystem::recursive_directory_iterator(root); it != std::filesystem::end(it); ++it) {
    const std::string rel = std::filesystem::relative(it->path(), root).string();
    if (it->is_directory() &&
        (rel.rfind("build", 0) == 0 || rel == "tests" || rel == "tools" || rel == "docs" || rel[0] == '.' ||
         rel.find("node_modules") != std::string::npos)) {
      it.disable_recursion_pending();
      continue;
    }
    const std::string ext = it->path().extension().string();
    if (!it->is_regular_file() || (ext != ".cpp" && ext != ".hpp" && ext != ".h")) continue;
    ++files;
    const std::string text = read(it->path().string());
    for (std::sregex_iterator m(text.begin(), text.end(), literal), end; m != end; ++m) {
      const std::string name = (*m)[1];
      if (rel == "comm/posix/environment.hpp") {
        seen.insert(name);
        continue;
      }
      if (name == "MAPTR_TICK_WAKE" && rel == "comm/lockstep/tick_filter.hpp") continue;
      ADD_FAILURE() << rel << " names \"" << name << "\" itself: use comm/posix/environment.hpp's constant"
                    << (table.count(name) ? "" : " (and add it to the table)");
    }
  }
  EXPECT_GT(files, 100);
  EXPECT_EQ(seen, table)
      << "a constant of comm/posix/environment.hpp is not in kEnvironment, or the other way round";
}

TEST(Reference, TheCommittedSettingsReferenceIsTheLists) {
  const std::string doc = std::string(MAPTR_SOURCE_DIR) + "/docs/SETTINGS.md";
  EXPECT_EQ(read(doc), maptr::deploy::report::settings_reference(maptr::deploy::report::all_settings(), true))
      << "docs/SETTINGS.md differs from the settings lists: "
         "build/bin/maptr fields --settings --markdown > docs/SETTINGS.md";
}

/// The data members of `name` in the header `path` (read as text: "TYPE NAME = ..." or "{...}").
std::set<std::string> members(const std::string& path, const std::string& name) {
  const std::string text = read(std::string(MAPTR_SOURCE_DIR) + "/" + path);
  const std::size_t from = text.find("struct " + name + " ");  // "{" or ": Base {"
  const std::size_t to = text.find("\n};", from);
  EXPECT_NE(from, std::string::npos) << path << " has no struct " << name;
  std::set<std::string> out;
  if (from == std::string::npos) return out;
  const std::string body = text.substr(from, to - from);
  const std::regex member(
      R"(\n\s+(?:double|int|bool|std::size_t|std::chrono::milliseconds)\s+([a-z_0-9]+)\s*[={])");
  for (std::sregex_iterator m(body.begin(), body.end(), member), end; m != end; ++m) out.insert((*m)[1]);
  return out;
}

TEST(Reference, EverySettingOfTheProcessesStructsIsListed) {
  std::set<std::string> listed;
  for (const auto& s : maptr::deploy::report::all_settings()) {
    EXPECT_TRUE(listed.insert(s.name).second) << s.name << " listed twice";
    EXPECT_FALSE(s.value.empty()) << s.name;
    EXPECT_FALSE(s.meaning.empty()) << s.name;
  }
  const std::tuple<const char*, const char*, const char*> structs[] = {
      {"deploy/fleet/config.hpp", "FleetConfig", "launcher."},
      {"plant/plant_config.hpp", "PlantNodeConfig", "plant."},
      {"control/level2/solver.hpp", "Level2SolverConfig", "level2."},
      {"control/central_core.hpp", "CentralConfig", "central."},
      {"control/group_core.hpp", "GroupConfig", "group."},
      {"control/level1/agent_core.hpp", "AgentConfig", "agent."}};
  // What config/core_configs.cpp sets from the scenario (its tick, the robot's size).
  const std::set<std::string> from_scenario = {"dt_s", "track_m", "wheel_radius_m"};
  std::size_t seen = 0;
  for (const auto& [path, name, prefix] : structs)
    for (const auto& m : members(path, name)) {
      ++seen;
      if (from_scenario.count(m)) continue;
      EXPECT_TRUE(listed.count(prefix + m))
          << name << "::" << m << " (" << path << ") is not in maptr fields --settings";
    }
  EXPECT_GT(seen, 40u);  // the scan found the structs' members
}

/// Every key path of a YAML node: maps joined with '.', a list's entries as "[]". A path the
/// table holds is a leaf even when its value is a list (a waypoint segment's points).
void key_paths(const YAML::Node& n, const std::string& path, const std::set<std::string>& known,
               std::set<std::string>& out) {
  if (!path.empty() && known.count(path)) {
    out.insert(path);
    return;
  }
  if (n.IsMap()) {
    for (auto it = n.begin(); it != n.end(); ++it)
      key_paths(it->second, path.empty() ? it->first.Scalar() : path + "." + it->first.Scalar(), known, out);
  } else if (n.IsSequence()) {
    for (const auto& e : n) key_paths(e, path + "[]", known, out);
  } else {
    out.insert(path);
  }
}

TEST(Reference, EveryKeyOfEveryExampleScenarioIsInTheReference) {
  std::set<std::string> known;
  for (const auto& f : maptr::config::reference_field_table()) known.insert(f.path);
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::string(MAPTR_SOURCE_DIR) + "/deploy/scenarios")) {
    if (e.path().extension() != ".yaml") continue;
    ++files;
    std::set<std::string> keys;
    key_paths(YAML::LoadFile(e.path().string()), "", known, keys);
    for (const auto& k : keys) EXPECT_TRUE(known.count(k)) << e.path().filename() << ": " << k << " is not in maptr fields";
  }
  EXPECT_GE(files, 3);
  // And the reference shows each of them.
  const std::string text = maptr::deploy::report::scenario_reference("", false);
  for (const auto& k : known) EXPECT_NE(text.find(k), std::string::npos) << k;
}

TEST(Reference, APrefixSelectsItsFieldsOnly) {
  const std::string control = maptr::deploy::report::scenario_reference("control.", false);
  EXPECT_NE(control.find("control.t_on_s"), std::string::npos);
  EXPECT_EQ(control.find("robot.track_m"), std::string::npos);
  EXPECT_EQ(maptr::deploy::report::scenario_field_count("no.such."), 0);
  EXPECT_GT(maptr::deploy::report::scenario_field_count("faults[]."), 4);
}

TEST(Reference, SummaryPatternsMatchRuntimeNamesOnly) {
  using maptr::records::summary_path_matches;
  EXPECT_TRUE(summary_path_matches("rejected_samples.<process>", "rejected_samples.L3"));
  EXPECT_TRUE(summary_path_matches("plant.tick_timing_us.<part>.p90", "plant.tick_timing_us.barrier.p90"));
  EXPECT_TRUE(summary_path_matches("failures[].at_s", "failures[].at_s"));
  EXPECT_TRUE(summary_path_matches("recording.recorded.<topic>", "recording.recorded.maptr/tick"));
  EXPECT_FALSE(summary_path_matches("rejected_samples.<process>", "rejected_samples"));
  EXPECT_FALSE(summary_path_matches("rejected_samples.<process>", "rejected_samples.L3.extra"));
  EXPECT_FALSE(summary_path_matches("failures[].at_s", "failures.at_s"));
  EXPECT_FALSE(summary_path_matches("energy_J", "energy_j"));
}

TEST(Reference, EverySummaryKeyHasATypeAndADescriptionAndIsListedOnce) {
  std::set<std::string> seen;
  for (const auto& f : maptr::records::summary_fields()) {
    SCOPED_TRACE(f.path);
    EXPECT_FALSE(f.type.empty());
    EXPECT_FALSE(f.description.empty());
    EXPECT_TRUE(seen.insert(f.path).second) << "listed twice";
  }
  EXPECT_GE(seen.size(), 100u);
}

}  // namespace
