#pragma once
// The execution of the fault schedule, free of DDS and processes: for each fault due (at a
// gate, from a command or from chaos), the rule of decide_fault() on its target's state, the
// action on the target, the line that says what was done and the record of the summary. The
// fleet's processes are reached through FaultTargets, which the launcher implements with
// signals and spawns and the tests with a stub.
#include <sys/types.h>

#include <string>
#include <vector>

#include "deploy/fleet/fault_schedule.hpp"

namespace maptr::deploy::fleet {

/// The processes a fault acts on (an agent, a controller, the plant or the discovery server).
class FaultTargets {
 public:
  virtual TargetState state_of(const std::string& target) = 0;
  virtual pid_t pid_of(const std::string& target) = 0;  ///< -1: none
  virtual void kill_target(const std::string& target) = 0;
  virtual void restart_target(const std::string& target) = 0;
  virtual void pause_target(const std::string& target, bool pause) = 0;

 protected:
  ~FaultTargets() = default;
};

/// What one fault did: the action and one line for the log ("" when skipped).
struct FaultOutcome {
  FaultAction action;
  std::string line;
};

class FaultExecution {
 public:
  FaultExecution(std::vector<config::FaultSpec> faults, FaultTargets& targets)
      : schedule_(std::move(faults)), targets_(targets) {}

  /// Takes out every scheduled fault due at a gate of simulated time gate_t.
  std::vector<config::FaultSpec> due(double gate_t) { return schedule_.due(gate_t); }
  /// Applies a process fault at simulated time at_s (wall clock wall_ms, ms since the epoch) and
  /// records it; origin: "scheduled", "chaos" or "command".
  FaultOutcome apply(const config::FaultSpec& f, double at_s, double wall_ms, const std::string& origin);
  /// The record of every fault, host faults included (they are applied by the placement).
  FaultSchedule& schedule() { return schedule_; }

 private:
  FaultSchedule schedule_;
  FaultTargets& targets_;
};

}  // namespace maptr::deploy::fleet
