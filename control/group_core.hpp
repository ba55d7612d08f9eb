#pragma once
// Group controller of one side: which of its agents run from the next tick.
//   mode all (the paper's NO): every live agent is active.
//   mode ec (energy-conscious):
//     - while the side's wheel speed is far from its reference (relative error above
//       cruise_leave, until it is back within cruise_enter) every live agent runs;
//     - in cruise, Level 2 chooses the count N_a every level2_period_s [s]: the problem is
//       built from tick k's inputs and handed to a Level2Runner; its outcome is applied at tick
//       k + d, d = round(level2_defer_s / dt_s) (d = 0: in tick k). A decision still pending
//       when cruise ends is dropped; the next starts only after the last one was applied;
//     - Level 3 (allocate() on the wear Ledger) chooses which agents every t_on_s [s], whenever
//       N_a or the number of active agents changes, and when an active agent reaches the
//       thermal limit thermal_limit_s [s] of continuous operation.
// Fault detection (control/diagnosis.hpp), when the tick carries the drive's measurements: an
// agent flagged faulty counts as not live (Level 2 counts one fewer, Level 3 never assigns it)
// until its probation is over; GroupDecision::faulty announces it (the plant disconnects it).
// The ledger after each step goes out with the group's status; the plant keeps the last one and
// a restarted controller resumes from it (resume()).
// Pure: explicit time (GroupInput::t), no DDS, no file, no clock (except the solver's diagnostic
// timing).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "control/diagnosis.hpp"
#include "control/level2/runner.hpp"
#include "control/level2/status.hpp"
#include "control/level3/ledger.hpp"
#include "control/tunable.hpp"
#include "model/params.hpp"

namespace maptr::control {

enum class GroupMode { kAll, kEnergyConscious };

/// The scenario's control.* fields the group reads, declared here and nowhere else: the member
/// with its default, and its row in group_tunables() (path, range, unit, description), which the
/// scenario's table takes as it is (control/tunable.hpp).
struct GroupTuning : DiagnosisTuning {
  double level2_period_s = 1.0;    ///< s between Level-2 decisions in cruise (paper: 1 Hz)
  double level2_defer_s = 0.1;     ///< s from a decision's inputs (tick k) to its use (tick k + d)
  int horizon = 10;                ///< Level-2 horizon, steps (paper: 10)
  double horizon_step_s = 0.1;     ///< Level-2 horizon step, s
  double t_on_s = 100.0;           ///< Level-3 period T_ON, s
  double thermal_limit_s = 600.0;  ///< max continuous active time of an agent, s
  bool oracle = false;             ///< also solve by exhaustive search and report its choice
  bool fault_detection = true;     ///< watch the agents when the tick carries measurements
};

inline std::vector<Tunable<GroupTuning>> group_tunables() {
  using T = GroupTuning;
  const auto above = Bounds::above;
  return {
      real_tunable<T>(
          "control.level2_period_s", [](T& t) -> double& { return t.level2_period_s; }, above(0, 1e6), "s",
          "Level-2 decision period (at least one tick)"),
      real_tunable<T>(
          "control.level2_defer_s", [](T& t) -> double& { return t.level2_defer_s; }, Bounds::closed(0, 60),
          "s",
          "a Level-2 decision uses tick k's inputs and is applied at tick k + round(this / dt), solved "
          "meanwhile on the group's worker thread (0: in tick k)"),
      count_tunable<T>(
          "control.horizon", [](T& t) -> int& { return t.horizon; }, Bounds::closed(1, 1000),
          "Level-2 horizon, steps"),
      real_tunable<T>(
          "control.horizon_step_s", [](T& t) -> double& { return t.horizon_step_s; }, above(0, 1e3), "s",
          "Level-2 horizon step"),
      real_tunable<T>(
          "control.t_on_s", [](T& t) -> double& { return t.t_on_s; }, above(0, 1e7), "s",
          "Level-3 period T_ON"),
      real_tunable<T>(
          "control.thermal_limit_s", [](T& t) -> double& { return t.thermal_limit_s; }, above(0, 1e7), "s",
          "longest continuous active time of an agent"),
      flag_tunable<T>(
          "control.oracle", [](T& t) -> bool& { return t.oracle; },
          "also run the exhaustive Level-2 search and report it"),
      flag_tunable<T>(
          "control.fault_detection", [](T& t) -> bool& { return t.fault_detection; },
          "the plant publishes what each wheel's drive measures and the groups isolate the agents whose "
          "measurements disagree with the motor model (docs/ARCHITECTURE.md \"Fault detection\")"),
  };
}

/// The tuning and what the group node knows of the run.
struct GroupConfig : GroupTuning {
  model::RobotParams robot;
  GroupMode mode = GroupMode::kEnergyConscious;
  double dt_s = 0.01;          ///< tick period, s
  double cruise_enter = 0.05;  ///< relative speed error at or below which cruise starts
  double cruise_leave = 0.20;  ///< relative speed error above which cruise ends
};

/// What the group reads from one tick.
struct GroupInput {
  long long tick = 0;
  double t = 0.0;                                 ///< s
  double v_x = 0.0, w = 0.0;                      ///< m/s, rad/s: body state at t
  double phidot_side = 0.0;                       ///< rad/s, this side's wheels
  double phidot_ref_L = 0.0, phidot_ref_R = 0.0;  ///< rad/s, references in force
  double battery_V = 0.0;                         ///< V, this side
  std::vector<uint8_t> live;                      ///< membership of this side (from the plant)
  std::vector<uint8_t> active;                    ///< assignment in force over [t_{k-1}, t_k]
  int n_other = 0;                                ///< other side's active count, relayed by central
  bool measured = false;                          ///< the tick carries the drive's measurements
  SideSample drives;                              ///< what the plant measured of each agent's drive
};

struct GroupDecision {
  std::vector<uint8_t> active;  ///< assignment from tick k+1
  int n_active = 0, n_live = 0;
  Level2Decision level2;    ///< the last Level-2 decision (its status kL2None in mode all)
  bool level2_ran = false;  ///< `level2` was applied at this tick
  uint64_t decisions = 0, reallocations = 0;
  std::vector<uint8_t> faulty;              ///< per agent: 0, or the Diagnosis it is isolated for
  std::vector<DiagnosisChange> diagnosed;   ///< flags raised or lowered at this tick
};

class GroupCore {
 public:
  /// side 0 = left, 1 = right; `resume`: the ledger a restarted controller goes on from (its
  /// size must be the side's agents), none for a fresh one. runner solves the Level-2 decisions
  /// (nullptr: an InlineLevel2Runner of the core's own); it must outlive the core.
  GroupCore(int side, const GroupConfig& config, std::optional<Ledger> resume = std::nullopt,
            Level2Runner* runner = nullptr);
  GroupDecision step(const GroupInput& in);
  const Ledger& ledger() const { return ledger_; }
  /// A restarted controller goes on from `ledger` (the side's last status the plant took; its
  /// size must be the side's agents), before its first step.
  void resume(Ledger ledger) {
    ledger_ = std::move(ledger);
    resumed_ = true;
  }
  bool resumed() const { return resumed_; }

 private:
  bool update_cruise(const GroupInput& in);
  /// The wear of the assignment in force over [t_{k-1}, t_k].
  void accrue_wear(const GroupInput& in);
  /// Runs Level 2 if in cruise and due; returns the wanted N_a; fills d's Level-2 fields.
  int decide_count(const GroupInput& in, bool cruising, GroupDecision& d, bool& realloc,
                   const std::vector<uint8_t>& next);
  void start_level2(const GroupInput& in, GroupDecision& d, int& target);
  void apply_level2(GroupDecision& d, int& target);

  /// A decision started and not applied yet.
  struct Pending {
    long long apply_tick = 0;
    double t_s = 0.0;
    int n_other = 0;
    bool stale = false;  ///< cruise ended after it started: dropped when it is due
  };

  int side_;
  GroupConfig c_;
  Ledger ledger_;
  std::unique_ptr<Level2Runner> own_runner_;
  Level2Runner* runner_;
  long long defer_ticks_ = 0;
  std::optional<Pending> pending_;
  bool resumed_ = false;
  double last_l2_t_ = kNeverS;
  bool cruise_ = false;
  GroupDecision last_;
  std::optional<SideDiagnosis> diagnosis_;
};

}  // namespace maptr::control
