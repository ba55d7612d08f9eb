// The scenario parser: every bad file refused with a ScenarioError naming the field and the
// value (in a short message), to_yaml() read back identical, command-line values checked
// through the same field table.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "config/scenario.hpp"

namespace {

using maptr::config::field_table;
using maptr::config::FieldInfo;
using maptr::config::FieldType;
using maptr::config::kMaxQuotedChars;
using maptr::config::kMaxScenarioBytes;
using maptr::config::load_scenario;
using maptr::config::parse_scenario;
using maptr::config::Scenario;
using maptr::config::ScenarioError;
using maptr::config::set_field;
using maptr::config::set_speed;
using maptr::config::to_yaml;

/// A message that stays one readable line even when the input is huge.
constexpr std::size_t kShortMessage = 400;

/// The message of the ScenarioError that parsing `yaml` throws ("" if it does not throw).
std::string refusal(const std::string& yaml) {
  try {
    parse_scenario(yaml, "test.yaml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

/// Parsing is refused, the message names the source and the field (and the value if given).
void expect_refused(const std::string& yaml, const std::string& field, const std::string& value = "") {
  const std::string m = refusal(yaml);
  ASSERT_FALSE(m.empty()) << "accepted:\n" << yaml;
  EXPECT_NE(m.find("test.yaml: "), std::string::npos) << m;
  EXPECT_NE(m.find(field), std::string::npos) << m;
  EXPECT_NE(m.find(value), std::string::npos) << m;
  EXPECT_LT(m.size(), kShortMessage) << m;
}

class TempDir {
 public:
  TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "maptr-scenario-XXXXXX").string();
    path_ = mkdtemp(tmpl.data());
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const std::string p = path_ + "/" + name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// A scenario text that sets `path` (a field_table() path) to `value`, everything else valid.
std::string yaml_setting(const std::string& path, const std::string& value) {
  const std::string seg = "trajectory.segments[].", fault = "faults[].";
  if (path.rfind(seg, 0) == 0) {
    const std::string key = path.substr(seg.size());
    std::string m = "type: arc, speed_mps: 1, duration_s: 5";
    if (key != "yaw_rate_rad_s" && key != "radius_m") m += ", yaw_rate_rad_s: 0.1";
    if (key == "type" || key == "speed_mps" || key == "duration_s")
      m = key == "type" ? "speed_mps: 1" : "type: straight";
    return "trajectory:\n  segments:\n    - {" + m + ", " + key + ": " + value + "}\n";
  }
  if (path.rfind(fault, 0) == 0) {
    const std::string key = path.substr(fault.size());
    std::string m = key == "target"   ? "action: kill, at_s: 1"
                    : key == "action" ? "target: L0, at_s: 1"
                                      : "target: L0, action: kill";
    return "faults:\n  - {" + m + ", " + key + ": " + value + "}\n";
  }
  const auto dot = path.find('.');
  if (dot == std::string::npos) return path + ": " + value + "\n";
  return path.substr(0, dot) + ":\n  " + path.substr(dot + 1) + ": " + value + "\n";
}

bool is_number(const FieldInfo& f) { return f.type == FieldType::kReal || f.type == FieldType::kInteger; }

// ---- Files that are not a scenario ----

TEST(Scenario, AnEmptyFileIsRefused) { expect_refused("", "(top level)"); }

TEST(Scenario, AFileOfOnlyCommentsIsRefused) { expect_refused("# nothing\n\n# here\n", "(top level)"); }

TEST(Scenario, ADocumentThatIsNotAMappingIsRefused) {
  expect_refused("- agents\n- 16\n", "(top level)", "must be a mapping");
  expect_refused("just words\n", "(top level)", "just words");
}

TEST(Scenario, TwoDocumentsAreRefused) { expect_refused("agents: 16\n---\nagents: 32\n", "(top level)"); }

TEST(Scenario, ABareSecondDocumentAfterAnEndMarkerIsRefused) {
  expect_refused("agents: 16\n...\nagents: 32\n", "(top level)");
  expect_refused("agents: 16\n...\n---\nagents: 32\n", "(top level)");
}

TEST(Scenario, InputOnWhichYamlCppLoadAllLoopsIsRefused) { expect_refused(",- b\n", "(top level)"); }

TEST(Scenario, InvalidYamlIsAScenarioError) { expect_refused("agents: [16\n", "not valid YAML"); }

TEST(Scenario, ADirectoryIsRefused) {
  TempDir d;
  try {
    load_scenario(d.path());
    FAIL() << "a directory was accepted";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(d.path()), std::string::npos) << e.what();
  }
}

TEST(Scenario, ADeviceIsRefused) { EXPECT_THROW(load_scenario("/dev/null"), ScenarioError); }

TEST(Scenario, AMissingFileIsRefused) {
  TempDir d;
  EXPECT_THROW(load_scenario(d.path() + "/none.yaml"), ScenarioError);
}

TEST(Scenario, AFileAboveTheSizeLimitIsRefusedWithAShortMessage) {
  TempDir d;
  const std::string p = d.write("big.yaml", "name: " + std::string(kMaxScenarioBytes, 'a') + "\n");
  try {
    load_scenario(p);
    FAIL() << "a file above the size limit was accepted";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("bytes"), std::string::npos) << e.what();
    EXPECT_LT(std::string(e.what()).size(), kShortMessage);
  }
  EXPECT_THROW(parse_scenario(std::string(kMaxScenarioBytes + 1, ' '), "text"), ScenarioError);
}

TEST(Scenario, AFileIsReadAndNamedInErrors) {
  TempDir d;
  const std::string p = d.write("s.yaml", "agents: 32\nname: two-sides\n");
  const Scenario s = load_scenario(p);
  EXPECT_EQ(s.robot.agents, 32);
  EXPECT_EQ(s.name, "two-sides");
  EXPECT_EQ(s.source, p);
  const std::string bad = d.write("bad.yaml", "agents: 18\n");
  try {
    load_scenario(bad);
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(bad + ": agents = 18", 0), 0u) << e.what();
  }
}

// ---- Keys ----

TEST(Scenario, ADuplicatedTopLevelKeyIsRefused) {
  expect_refused("agents: 16\nagents: 32\n", "agents", "duplicate");
}

TEST(Scenario, ADuplicatedNestedKeyIsRefused) {
  expect_refused("control:\n  kp: 0.5\n  kp: 0.7\n", "control.kp", "duplicate");
  expect_refused("robot: {track_m: 0.2}\nrobot: {track_m: 0.3}\n", "robot", "duplicate");
}

TEST(Scenario, ADuplicatedKeyInASegmentIsRefused) {
  expect_refused("trajectory:\n  segments:\n    - {speed_mps: 1, speed_mps: 2, duration_s: 5}\n",
                 "trajectory.segments[0].speed_mps", "duplicate");
}

TEST(Scenario, AnUnknownKeyIsRefused) { expect_refused("robot:\n  colour: red\n", "robot.colour", "red"); }

TEST(Scenario, AKeyThatIsNotANameIsRefused) { expect_refused("? [a, b]\n: 1\n", "a key must be a name"); }

// ---- Values ----

TEST(Scenario, EveryNumericFieldRefusesNanAndInfinities) {
  for (const FieldInfo& f : field_table()) {
    if (!is_number(f)) continue;
    for (const char* v : {".nan", ".inf", "-.inf"}) {
      SCOPED_TRACE(f.path + " = " + v);
      const std::string field =
          f.path.find("[]") == std::string::npos ? f.path : f.path.substr(f.path.rfind('.') + 1);
      expect_refused(yaml_setting(f.path, v), field, v);
    }
  }
}

TEST(Scenario, EveryNumericFieldWhoseRangeExcludesZeroRefusesZero) {
  int refused = 0;
  for (const FieldInfo& f : field_table()) {
    if (!is_number(f) || f.range.contains(0.0)) continue;
    SCOPED_TRACE(f.path);
    expect_refused(yaml_setting(f.path, "0"), f.path.substr(f.path.rfind('.') + 1), "0");
    ++refused;
  }
  EXPECT_GE(refused, 15);  // durations, rates, masses, lengths, periods, the arc radius
}

TEST(Scenario, EveryNumericFieldRefusesAValueAboveItsRange) {
  for (const FieldInfo& f : field_table()) {
    if (!is_number(f)) continue;
    SCOPED_TRACE(f.path);
    expect_refused(yaml_setting(f.path, "1e12"), f.path.substr(f.path.rfind('.') + 1), "1e12");
  }
}

TEST(Scenario, AnArcOfZeroRadiusIsRefused) {
  expect_refused("trajectory:\n  segments:\n    - {type: arc, speed_mps: 1, radius_m: 0, duration_s: 5}\n",
                 "trajectory.segments[0].radius_m", "0");
}

TEST(Scenario, AnArcWithoutYawRateIsRefused) {
  expect_refused("trajectory:\n  segments:\n    - {type: arc, speed_mps: 1, duration_s: 5}\n",
                 "trajectory.segments[0].yaw_rate_rad_s");
}

TEST(Scenario, AnArcWithANanYawRateNamesTheYawRate) {
  const std::string m = refusal(
      "trajectory:\n  segments:\n    - {type: arc, speed_mps: 1, yaw_rate_rad_s: .nan, duration_s: 5}\n");
  EXPECT_NE(m.find("trajectory.segments[0].yaw_rate_rad_s = .nan"), std::string::npos) << m;
  EXPECT_EQ(m.find("speed_mps"), std::string::npos) << m;
}

TEST(Scenario, ARadiusOutsideAnArcIsRefused) {
  expect_refused(
      "trajectory:\n  segments:\n    - {type: straight, speed_mps: 1, radius_m: 5, duration_s: 5}\n",
      "trajectory.segments[0].radius_m", "only an arc");
}

TEST(Scenario, AnArcRadiusGivesTheYawRate) {
  const Scenario s = parse_scenario(
      "robot: {driver: bidirectional}\n"
      "trajectory:\n  segments:\n    - {type: arc, speed_mps: 1.5, radius_m: -3, duration_s: 5}\n", "t");
  EXPECT_DOUBLE_EQ(s.trajectory.segments[0].yaw_rate_rad_s, -0.5);
}

TEST(Scenario, InfiniteStopDecelerationIsRefused) {
  expect_refused("control:\n  stop_decel_mps2: .inf\n", "control.stop_decel_mps2", ".inf");
}

TEST(Scenario, InfiniteTrajectoryAccelerationIsRefused) {
  expect_refused("trajectory:\n  accel_mps2: .inf\n  segments: [{speed_mps: 1}]\n", "trajectory.accel_mps2",
                 ".inf");
}

TEST(Scenario, APidWithNeitherProportionalNorIntegralGainIsRefused) {
  expect_refused("control: {kp: 0, ki: 0}\n", "control.ki", "0");
  EXPECT_NO_THROW(parse_scenario("control: {kp: 0, ki: 0.5}\n", "t.yaml"));
  EXPECT_NO_THROW(parse_scenario("control: {kp: 0.5, ki: 0}\n", "t.yaml"));
}

TEST(Scenario, AWheelSpeedBeyondTheMotorsIsRefused) {
  expect_refused("trajectory:\n  segments:\n    - {type: straight, speed_mps: 40, duration_s: 5}\n",
                 "trajectory.segments[0].speed_mps", "40");
}

TEST(Scenario, AnIntegerTooLargeForItsTypeIsAScenarioError) {
  expect_refused("agents: 99999999999999999999\n", "agents", "must be an integer");
}

TEST(Scenario, AWrongTypeIsRefused) {
  expect_refused("agents: sixteen\n", "agents", "sixteen");
  expect_refused("realtime: maybe\n", "realtime", "maybe");
  expect_refused("duration_s: [1, 2]\n", "duration_s", "must be a number");
}

TEST(Scenario, AFaultOnAnAgentTheRobotDoesNotHaveIsRefused) {
  expect_refused("faults: [{target: L9, action: kill, at_s: 1}]\n", "faults[0].target", "L9");
  expect_refused("faults: [{target: L1, action: kill, at_s: 61}]\n", "faults[0].at_s", "61");
}

TEST(Scenario, PausesAndResumesAreFaultsAndAResumeNeedsAPause) {
  EXPECT_EQ(
      refusal("faults: [{target: L1, action: pause, at_s: 5}, {target: L1, action: resume, at_s: 8}]\n"), "");
  // In time order, whatever the order of the list.
  EXPECT_EQ(refusal("faults: [{target: central, action: resume, at_s: 8}, {target: central, action: pause, "
                    "at_s: 5}]\n"),
            "");
  expect_refused("faults: [{target: L1, action: resume, at_s: 8}]\n", "faults[0].action", "resume");
  expect_refused("faults: [{target: L1, action: pause, at_s: 9}, {target: L1, action: resume, at_s: 8}]\n",
                 "faults[1].action", "resume");
  expect_refused("faults: [{target: L1, action: pause, at_s: 5}, {target: L2, action: resume, at_s: 8}]\n",
                 "faults[1].action", "resume");
  // A kill ends the pause: nothing is left to resume.
  expect_refused(
      "faults: [{target: L1, action: pause, at_s: 5}, {target: L1, action: kill, at_s: 6},"
      " {target: L1, action: resume, at_s: 8}]\n",
      "faults[2].action", "resume");
  expect_refused("faults: [{target: plant, action: pause, at_s: 5}]\n", "faults[0].target", "plant");
  expect_refused("faults: [{target: L1, action: freeze, at_s: 5}]\n", "faults[0].action", "freeze");
}

// ---- Names and message length ----

TEST(Scenario, ANameOf300CharactersIsRefusedInAShortMessage) {
  const std::string m = refusal("name: " + std::string(300, 'n') + "\n");
  ASSERT_FALSE(m.empty());
  EXPECT_NE(m.find("name = nnnn"), std::string::npos) << m;
  EXPECT_NE(m.find("…"), std::string::npos) << m;
  EXPECT_LT(m.size(), kShortMessage) << m;
}

TEST(Scenario, ANameThatLeavesItsFolderIsRefused) {
  expect_refused("name: ../escape\n", "name", "../escape");
  expect_refused("name: a/b\n", "name", "a/b");
  expect_refused("name: ..\n", "name");
  expect_refused("name: \"\"\n", "name");
  expect_refused("name: \"a b\"\n", "name");
}

TEST(Scenario, ANameOfTheSafeCharactersIsAccepted) {
  EXPECT_EQ(parse_scenario("name: table-pow_13.2kg-ec\n", "t").name, "table-pow_13.2kg-ec");
}

TEST(Scenario, ALongValueIsQuotedShort) {
  const std::string m = refusal("colour: " + std::string(10000, 'z') + "\n");
  ASSERT_FALSE(m.empty());
  EXPECT_NE(m.find("colour = " + std::string(kMaxQuotedChars, 'z') + "…"), std::string::npos) << m;
  EXPECT_EQ(m.find(std::string(kMaxQuotedChars + 1, 'z')), std::string::npos);
  EXPECT_LT(m.size(), kShortMessage);
}

TEST(Scenario, ALongUnknownKeyIsQuotedShort) {
  const std::string m = refusal(std::string(1000, 'k') + ": 1\n");
  ASSERT_FALSE(m.empty());
  EXPECT_NE(m.find("unknown key"), std::string::npos) << m;
  EXPECT_LT(m.size(), kShortMessage);
}

// ---- Round trip and the table ----

TEST(Scenario, ToYamlReadsBackIdentical) {
  const std::string text =
      "name: arc.1\nagents: 32\nmotor: II\ngross_mass_kg: 14.4\nmode: all\nduration_s: 30\ntick_hz: 200\n"
      "trace_every: 3\nstop_below_speed_pct: 12.5\n"
      "robot: {track_m: 0.25, yaw_inertia_kgm2: 0.3, driver: bidirectional, regeneration: true, "
      "charge_limit_A: 2.5}\n"
      "battery: {initial_discharge_mAh: 6000, h: -1.851e-14}\ncontrol: {kp: 0.7, ki: 1.3, oracle: true}\n"
      "trajectory:\n  accel_mps2: 0.5\n  segments:\n    - {type: straight, speed_mps: 1.5, duration_s: 10}\n"
      "    - {type: arc, speed_mps: 1, radius_m: -3, duration_s: 10}\n    - {type: stop, duration_s: 5}\n"
      "faults:\n  - {target: L3, action: kill, at_s: 5}\n  - {target: group-R, action: kill, at_s: 6}\n"
      "  - {target: group-R, action: restart, at_s: 7.25}\n";
  for (const Scenario& s : {parse_scenario(text, "t"), Scenario{}}) {
    const std::string y = to_yaml(s);
    const Scenario back = parse_scenario(y, "t");
    EXPECT_EQ(to_yaml(back), y);
    EXPECT_EQ(back.robot.gross_mass_kg, s.robot.gross_mass_kg);
    EXPECT_EQ(back.robot.battery.h, s.robot.battery.h);
    EXPECT_EQ(back.robot.motor.back_emf_Vs, s.robot.motor.back_emf_Vs);
    ASSERT_EQ(back.trajectory.segments.size(), s.trajectory.segments.size());
    for (std::size_t i = 0; i < s.trajectory.segments.size(); ++i) {
      EXPECT_EQ(back.trajectory.segments[i].yaw_rate_rad_s, s.trajectory.segments[i].yaw_rate_rad_s);
      EXPECT_EQ(back.trajectory.segments[i].type, s.trajectory.segments[i].type);
    }
    ASSERT_EQ(back.faults.size(), s.faults.size());
  }
}

TEST(Scenario, EveryFieldHasARangeAUnitAndADescription) {
  const auto table = field_table();
  EXPECT_GE(table.size(), 45u);
  for (const FieldInfo& f : table) {
    SCOPED_TRACE(f.path);
    EXPECT_FALSE(f.description.empty());
    if (is_number(f)) {  // a finite range, never NaN
      EXPECT_TRUE(std::isfinite(f.range.min) && std::isfinite(f.range.max));
      EXPECT_LT(f.range.min, f.range.max);
      EXPECT_FALSE(f.unit.empty());
      EXPECT_FALSE(f.range.contains(std::nan("")));
    }
    if (f.type == FieldType::kText) {
      EXPECT_TRUE(!f.choices.empty() || !f.rule.empty());
    }
    if (!f.input_only && f.type != FieldType::kText) {  // a fault's target and action have none
      EXPECT_FALSE(f.default_value.empty());
    }
  }
}

TEST(Scenario, ValidateChecksValuesSetInCode) {
  Scenario s;
  s.duration_s = std::nan("");
  try {
    s.validate();
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("duration_s"), std::string::npos) << e.what();
  }
  Scenario t;
  t.trajectory.segments[0].speed_mps = -1;
  EXPECT_THROW(t.validate(), ScenarioError);
}

// ---- Command-line values ----

TEST(Scenario, SetFieldAcceptsValuesAsTheFileWould) {
  Scenario s;
  set_field(s, "gross_mass_kg", "20.5", "--gross-kg");
  set_field(s, "agents", "32", "--agents");
  set_field(s, "motor", "II", "--motor");
  set_field(s, "mode", "all", "--mode");
  set_field(s, "tick_hz", "250", "--tick-hz");
  set_speed(s, "3.5", "--speed");
  EXPECT_EQ(s.robot.gross_mass_kg, 20.5);
  EXPECT_EQ(s.robot.agents, 32);
  EXPECT_EQ(s.robot.motor.rated_voltage_V, 6.0);  // the whole Type-II motor
  EXPECT_EQ(s.mode, "all");
  EXPECT_EQ(s.tick_hz, 250.0);
  EXPECT_EQ(s.trajectory.segments[0].speed_mps, 3.5);
  EXPECT_NO_THROW(s.validate());
  set_field(s, "robot.agents", "8", "--agents");  // the struct's path names the same field
  set_field(s, "robot.gross_mass_kg", "9", "--gross-kg");
  EXPECT_EQ(s.robot.agents, 8);
  EXPECT_EQ(s.robot.gross_mass_kg, 9.0);
}

TEST(Scenario, SetFieldRefusesWhatTheFileWould) {
  Scenario s;
  const auto refused = [&s](const std::string& path, const std::string& v, const std::string& origin) {
    try {
      path.empty() ? set_speed(s, v, origin) : set_field(s, path, v, origin);
    } catch (const ScenarioError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  for (const auto& m :
       {refused("", "-5", "--speed"), refused("", "nan", "--speed"), refused("", ".nan", "--speed")}) {
    EXPECT_EQ(m.rfind("--speed: trajectory.segments[].speed_mps = ", 0), 0u) << m;
  }
  EXPECT_NE(refused("gross_mass_kg", "-3", "--gross-kg").find("--gross-kg: gross_mass_kg = -3"),
            std::string::npos);
  EXPECT_NE(refused("agents", "18", "--agents").find("agents = 18"), std::string::npos);
  EXPECT_NE(refused("agents", "16.5", "--agents").find("must be an integer"), std::string::npos);
  EXPECT_NE(refused("mode", "fast", "--mode").find("mode = fast"), std::string::npos);
  EXPECT_NE(refused("duration_s", "inf", "--duration").find("duration_s"), std::string::npos);
  EXPECT_NE(refused("colour", "red", "--colour").find("not a scenario field"), std::string::npos);
  EXPECT_NE(refused("control.level2_defer_s", "-0.1", "scenario").find("control.level2_defer_s = -0.1"),
            std::string::npos);
  EXPECT_NE(refused("control.level2_defer_s", "61", "scenario").find("control.level2_defer_s = 61"),
            std::string::npos);
  EXPECT_EQ(s.robot.gross_mass_kg, Scenario{}.robot.gross_mass_kg);  // nothing set by a refusal
  EXPECT_EQ(s.trajectory.segments[0].speed_mps, 10.0);
}

}  // namespace

TEST(Scenario, TheTickFilterIsOnInEcAndOffInAllUnlessTheFileSaysOtherwise) {
  EXPECT_TRUE(parse_scenario("mode: ec\n", "test.yaml").uses_tick_filter());
  EXPECT_FALSE(parse_scenario("mode: all\n", "test.yaml").uses_tick_filter());
  EXPECT_TRUE(parse_scenario("mode: all\ntick_filter: true\n", "test.yaml").uses_tick_filter());
  EXPECT_FALSE(parse_scenario("mode: ec\ntick_filter: false\n", "test.yaml").uses_tick_filter());
  EXPECT_TRUE(parse_scenario("mode: ec\ntick_filter: auto\n", "test.yaml").uses_tick_filter());
  expect_refused("tick_filter: sometimes\n", "tick_filter", "sometimes");
}

TEST(Scenario, ThePlantsLockStepThreadRunsAtFifoPriorityOneUnlessTold) {
  EXPECT_EQ(parse_scenario("mode: ec\n", "test.yaml").plant_priority, 1);
  EXPECT_EQ(parse_scenario("plant_priority: 0\n", "test.yaml").plant_priority, 0);
  EXPECT_EQ(parse_scenario("plant_priority: 99\n", "test.yaml").plant_priority, 99);
  expect_refused("plant_priority: 100\n", "plant_priority", "100");
  expect_refused("plant_priority: -1\n", "plant_priority", "-1");
  expect_refused("plant_priority: 1.5\n", "plant_priority", "1.5");
}
