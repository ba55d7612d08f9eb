#pragma once
// Scenario: the typed configuration every process reads (the launcher resolves command-line
// overrides and hands each child the same resolved file). Defaults live in the structs;
// load_scenario() validates once and refuses bad input with the file, the field and the value.
#include <stdexcept>
#include <string>
#include <vector>

#include "control/trajectory.hpp"
#include "model/params.hpp"

namespace maptr::config {

using control::Segment;
using control::Trajectory;

class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ControlConfig {
  model::PidParams pid;
  double level2_period_s = 1.0;      ///< Level-2 decision period, s (paper: 1 Hz)
  int horizon = 10;                  ///< Level-2 horizon, steps (paper: 10)
  double horizon_step_s = 0.1;       ///< Level-2 horizon step, s
  double t_on_s = 100.0;             ///< Level-3 period T_ON, s
  double thermal_limit_s = 600.0;    ///< max continuous active time of an agent, s
  bool oracle = false;               ///< also run the exhaustive Level-2 search and report it
  double group_hold_s = 1.0;         ///< agents hold the last assignment this long without their group, s
  double central_timeout_s = 1.0;    ///< agents ramp to a stop after this long without central, s
  double stop_decel_mps2 = 2.0;      ///< deceleration of that ramp, m/s^2
};

struct FaultSpec {
  std::string target;   ///< "L3", "R0", "group-L", "group-R", "central", "plant"
  std::string action;   ///< "kill" | "restart"
  double at_s = 0.0;    ///< simulated time, s
};

struct Scenario {
  std::string name = "default";
  std::string source;              ///< file it came from ("" for defaults)
  std::string mode = "ec";         ///< "all" (paper's NO) | "ec" (energy-conscious)
  double duration_s = 60.0;        ///< simulated, s
  double tick_hz = 100.0;          ///< Level-1 / plant tick rate, Hz
  bool realtime = false;           ///< pace ticks to the wall clock
  int trace_every = 1;             ///< write every n-th tick to trace.csv
  double initial_discharge_mAh = 0.0;  ///< battery state at start (both groups), mAh
  /// End the run once the speed has stayed more than this many percent below its reference
  /// for 5 s after having reached it (0: never; the battery experiment runs until then).
  double stop_below_speed_pct = 0.0;
  model::RobotParams robot;
  ControlConfig control;
  Trajectory trajectory;
  std::vector<FaultSpec> faults;

  double dt() const { return 1.0 / tick_hz; }
  long long ticks() const;
  void validate() const;   ///< throws ScenarioError naming the field and the value
};

/// Reads and validates a scenario file. Unknown keys and wrong types are errors.
Scenario load_scenario(const std::string& path);
/// Same from text (source names it in errors).
Scenario parse_scenario(const std::string& yaml_text, const std::string& source);
/// Writes the resolved scenario (every field) as YAML.
std::string to_yaml(const Scenario& s);

/// Agent names: L0..L{N/2-1}, R0.. ; parse returns false on a malformed name.
std::string agent_name(int side, int index);
bool parse_agent_name(const std::string& name, int& side, int& index);

}  // namespace maptr::config
