#pragma once
// Scenario: the typed configuration every process reads (the launcher resolves command-line
// overrides and hands each child the same resolved file). Defaults live in the structs.
// Every field is declared once, in a table (scenario.cpp): its YAML path, type, range, unit and
// description. Parsing, validation, to_yaml() and the error messages all come from that table;
// field_table() lists it. A bad scenario is refused with a ScenarioError naming the file, the
// field and the value.
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "control/central_core.hpp"
#include "control/group_core.hpp"
#include "control/level1/agent_core.hpp"
#include "control/trajectory.hpp"
#include "model/params.hpp"

namespace maptr::config {

using control::Segment;
using control::Trajectory;

class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Largest scenario file accepted, bytes.
constexpr std::size_t kMaxScenarioBytes = 1u << 20;
/// Longest scenario name, characters; a name is made of A-Z a-z 0-9 . _ - and does not start
/// with '.', so that it is one safe folder name (runs/<date>-<name>).
constexpr std::size_t kMaxNameLength = 64;
/// Values (and unknown keys) are quoted in error messages up to this many bytes, then "…".
constexpr std::size_t kMaxQuotedChars = 80;

/// The `control` section: each core's tuning, declared in the core's header with its defaults
/// (a core takes its part whole: config/core_configs.cpp), and the plant's path check. The
/// table (scenario_fields.cpp) gives every field its YAML path control.NAME, range and meaning.
struct ControlConfig : control::AgentTuning, control::GroupTuning, control::CentralTuning {
  double path_tolerance_m = 0.5;  ///< a run whose cross-track error exceeds this is degraded, m
};

struct FaultSpec {
  std::string target;  ///< "L3", "R0", "group-L", "group-R", "central", "plant", "discovery"; a host "h1"
  std::string action;  ///< "kill" | "restart" | "pause" | "resume" (a process); "kill-host" | "partition" | "heal" (a host);
                       ///< "fault" | "clear" (an agent that runs on: a motor or software fault, docs/MODEL.md "Motor faults")
  double at_s = 0.0;   ///< simulated time, s
  std::string mode;    ///< action fault: open, short, torque, resistance, stuck (motor); sensor, erratic, liar (agent)
  double value = 0.0;  ///< action fault: torque/resistance F, stuck V [V], sensor B [rad/s], erratic S [V]
  /// Where it was given, for messages: "" for the scenario file's faults[i], else the option
  /// as typed ("--kill L3@100", "--chaos 7"). Not a scenario field.
  std::string origin;

  /// A fault without mode: a process's or a host's (kill, restart, pause, ...).
  static FaultSpec of(std::string target, std::string action, double at_s) {
    FaultSpec f;
    f.target = std::move(target);
    f.action = std::move(action);
    f.at_s = at_s;
    return f;
  }
};

/// True for the actions the fleet's processes apply by themselves at their tick (fault, clear):
/// no process is signalled and the plant holds no gate for them.
bool is_agent_fault_action(const std::string& action);
/// Why a fault's mode and value do not fit its action ("" when they do); `field` is set to the
/// field at fault ("mode" or "value"). The rules: action fault needs a mode, with a value for
/// torque (0, 1], resistance [1, 100], stuck (the driver's range at the rated voltage), sensor
/// (nonzero, |B| <= 1000 rad/s), erratic (0, 100] V, and none (0) for open, short and liar;
/// every other action takes neither.
std::string fault_mode_problem(const FaultSpec& f, const model::RobotParams& robot, std::string& field);
/// The first tick k with k dt >= at_s: when the plant and an agent apply a fault or clear at at_s.
long long first_tick_at(double at_s, double dt_s);

/// A fault that contradicts the schedule before it: the index into the list, the field at
/// fault ("action", "target" or "at_s") and why.
struct ScheduleProblem {
  std::size_t index = 0;
  std::string field;
  std::string why;
};
/// The first contradiction in a schedule, taken in time order (ties in list order), or nullopt.
/// A process is running until killed; a kill needs it running or paused (not dead), a restart
/// needs it dead, a pause needs it running, a resume needs it paused; the plant is never
/// restarted, and nothing is scheduled after its kill (the run ends there); the discovery server
/// is restarted by the launcher itself. A partition needs the host linked, a heal needs it cut
/// (by a partition or a kill-host). After a kill-host the processes' states are not followed
/// (which processes a host holds is the launcher's placement). The agents' own faults (fault,
/// clear) are not followed either: a second fault replaces the first, a clear of a healthy agent
/// does nothing.
std::optional<ScheduleProblem> schedule_problem(const std::vector<FaultSpec>& faults);

/// True for the actions whose target is a host (kill-host, partition, heal).
bool is_host_action(const std::string& action);
/// Parses a host name "h<index>" (h0, h1, ...).
bool parse_host_name(const std::string& name, int& index);
std::string host_name(int index);

/// Most hosts of one fleet.
constexpr int kMaxHosts = 64;

/// One host of a fleet spread over several (deploy/fleet/hosts.hpp runs them). Without an
/// address the launcher makes the host a network namespace of this machine; with one, the
/// processes placed there are started through `command` (e.g. "ssh user@board1"), which must
/// reach a machine whose MAPTR binaries and run folder are at the same paths as here.
struct HostSpec {
  std::string address;  ///< IPv4 address of a real machine ("" : a namespace)
  std::string command;  ///< command prefix that starts a process there
};

/// The hosts of a run: none (every process on this machine, shared memory and loopback) or
/// `count` hosts h0..h(count-1). Placement: "NAME=HOST" rules (NAME a process, HOST a host
/// name); every process without a rule is placed by deploy::fleet::default_placement().
struct HostsConfig {
  int count = 0;
  std::vector<HostSpec> machines;      ///< empty, or one per host
  std::vector<std::string> placement;  ///< "L3=h2", "central=h1", ...
  std::string launcher_address;        ///< real machines: this machine's address they reach
  /// A lost host's controllers (central, the groups) start again on a surviving host.
  bool failover = true;
  /// Namespace hosts reached over ssh (ssh_servers.hpp): the rehearsal of real machines.
  bool ssh = false;
  bool enabled() const { return count > 0; }
};

struct Scenario {
  std::string name = "default";
  std::string source;                  ///< file it came from ("" for defaults)
  std::string mode = "ec";             ///< "all" (paper's NO) | "ec" (energy-conscious)
  double duration_s = 60.0;            ///< simulated, s
  double tick_hz = 100.0;              ///< Level-1 / plant tick rate, Hz
  bool realtime = false;               ///< pace ticks to the wall clock
  int trace_every = 1;                 ///< write every n-th tick to trace.csv
  std::string record = "all";          ///< run.mcap: "all" topics, "plant" (ticks, gates, events), "none"
  std::string record_compression = "zstd";  ///< run.mcap's chunks: "none", "lz4" or "zstd"
  /// "auto" (on in ec, off in all), "true" or "false": an agent takes only the ticks it answers
  /// (comm/lockstep/tick_filter.hpp). In `all` every agent answers every tick, so a filter there only
  /// costs the plant its evaluation and every tick its filter signatures (BENCHMARKS.md).
  std::string tick_filter = "auto";
  /// SCHED_FIFO priority of the plant's lock-step thread (comm::make_thread_realtime), which
  /// integrates and publishes each tick and sleeps while the answers come: the agents it wakes
  /// then no longer preempt it halfway through a publish. 0: normal scheduling. Without the
  /// privilege the plant runs normally and says so (plant.json `loop_scheduling`).
  int plant_priority = 1;
  double initial_discharge_mAh = 0.0;  ///< battery state at start (both groups), mAh
  /// End the run once the speed has stayed more than this many percent below its reference
  /// for 5 s after having reached it (0: never; the battery experiment runs until then).
  double stop_below_speed_pct = 0.0;
  model::RobotParams robot;
  ControlConfig control;
  Trajectory trajectory;
  std::vector<FaultSpec> faults;
  HostsConfig hosts;

  double dt() const { return 1.0 / tick_hz; }
  /// Whether the plant filters the ticks it sends each agent (tick_filter resolved by mode).
  bool uses_tick_filter() const { return tick_filter == "true" || (tick_filter == "auto" && mode == "ec"); }
  long long ticks() const;
  /// Checks every field against its range in the table, then the rules that tie fields
  /// together (wheel speed within the motors' reach, fault times within the run, ...).
  /// Throws ScenarioError naming the field and the value.
  void validate() const;
};

/// Reads and validates a scenario file. Refused (ScenarioError): a path that is not a regular
/// file, a file above kMaxScenarioBytes, an empty document, more than one document, a
/// document that is not a mapping, unknown or duplicated keys, wrong types, values out of range.
Scenario load_scenario(const std::string& path);
/// Same from text (source names it in errors).
Scenario parse_scenario(const std::string& yaml_text, const std::string& source);
/// Writes the resolved scenario (every field) as YAML; parse_scenario() reads it back identical.
std::string to_yaml(const Scenario& s);

// ---- The field table ----

enum class FieldType { kReal, kInteger, kBool, kText };

/// Allowed values of a number: between min and max, each end open or closed; never NaN or
/// infinite; optionally not zero, and (integers) a multiple of `multiple_of`.
struct Range {
  double min = 0.0;
  double max = 0.0;
  bool min_open = false;
  bool max_open = false;
  bool nonzero = false;
  long long multiple_of = 1;
  bool contains(double v) const;
  std::string describe() const;  ///< e.g. "(0, 1e+06]"
};

/// One field of the table, as documentation and tests see it.
struct FieldInfo {
  /// YAML path: "duration_s", "robot.track_m", "trajectory.segments[].speed_mps", "faults[].at_s".
  std::string path;
  FieldType type = FieldType::kReal;
  Range range;                       ///< numbers
  std::vector<std::string> choices;  ///< text: the values accepted
  std::string rule;                  ///< text: further values accepted, in words ("" none)
  std::string unit;                  ///< SI unit, "1" for a pure number, "" for text and bools
  std::string description;           ///< one line
  std::string default_value;         ///< as to_yaml() writes it ("" for an input-only field)
  bool input_only = false;           ///< read from files, not kept (e.g. an arc's radius_m)
};

/// Every field: the scenario's own, then those of a trajectory segment and of a fault.
std::vector<FieldInfo> field_table();
/// The fields of the `hosts` section (read by hand: a list of machines and placement rules).
std::vector<FieldInfo> host_field_table();
/// Every field a scenario file may hold: field_table() and host_field_table(), as `maptr
/// fields` and docs/SCENARIO.md list them.
std::vector<FieldInfo> reference_field_table();

// ---- Command-line values, through the same table ----
//
// Options of `maptr run` and the scenario paths they set:
//   --agents N        -> agents                (robot.agents in the struct)
//   --gross-kg KG     -> gross_mass_kg         (robot.gross_mass_kg in the struct)
//   --motor I|II      -> motor                 (robot.motor in the struct)
//   --mode all|ec     -> mode
//   --duration S      -> duration_s
//   --tick-hz HZ      -> tick_hz
//   --trace-every N   -> trace_every
//   --record WHAT     -> record
//   --speed MPS       -> set_speed(): speed_mps of every segment that is not a stop
// set_field() also takes the struct's paths robot.agents, robot.gross_mass_kg and robot.motor
// for those three. Call Scenario::validate() once all values are set (the rules that tie
// fields together).

/// Parses and range-checks one value exactly as the file would and stores it. `path` is a
/// scenario field of field_table() (not a list's); `origin` names where the value came from
/// (e.g. "--gross-kg") in the error.
void set_field(Scenario& s, const std::string& path, const std::string& value, const std::string& origin);
/// Sets speed_mps of every segment that moves (type other than "stop"), checked against the
/// segment table's range.
void set_speed(Scenario& s, const std::string& value, const std::string& origin);
/// Sets duration_s as set_field() does; a duration longer than the trajectory lengthens its
/// last segment (`maptr run --duration`, `maptr compare --duration`).
void set_duration(Scenario& s, const std::string& value, const std::string& origin);

/// Agent names: L0..L{N/2-1}, R0.. ; parse returns false on a malformed name.
std::string agent_name(int side, int index);
bool parse_agent_name(const std::string& name, int& side, int& index);

}  // namespace maptr::config
