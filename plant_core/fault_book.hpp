#pragma once
// The agents' own faults as the plant keeps them (scenario actions fault and clear): each applied
// at its first tick, the motor faults in force (the plant integrates them, model/motor_fault.hpp),
// and the record of every fault against what the groups announced: when it was detected and
// isolated, what it was diagnosed as, when it was cleared and the agent let back. A flag the
// groups raise on an agent with no fault in force is a false detection. Pure: explicit time.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "model/motor_fault.hpp"

namespace maptr::plant_core {

/// A fault or clear of one agent, at tick `tick`.
struct AgentFaultEvent {
  long long tick = 0;
  int side = 0, index = 0;
  bool clear = false;
  std::string
      mode;  ///< fault: open, short, torque, resistance, stuck (the motor); sensor, erratic, liar (the agent)
  double value = 0.0;
};

/// One injected fault and what became of it. Times in s of simulated time.
struct AgentFaultRecord {
  std::string target, mode;
  double value = 0.0;
  double injected_s = 0.0;
  std::optional<double> detected_s;  ///< its group first flagged the agent (status of that tick)
  std::optional<double> isolated_s;  ///< from then on not assigned, not counted (the next tick)
  std::string diagnosed_mode;        ///< what the group took it for ("" if never detected)
  int relapses = 0;                  ///< flagged again after a probation
  std::optional<double> cleared_s;
  std::optional<double> readmitted_s;  ///< let back after its (last) probation
  /// Ticks in which the fault acted on the drive (its agent drove, or its winding carried a
  /// current it was not asked for): a fault that never acted cannot be seen, and did no harm.
  long long exposed_ticks = 0;
};

/// A change of a group's flag on one agent.
struct DiagnosisEvent {
  double t_s = 0.0;
  std::string target;
  std::string diagnosed;         ///< "" : let back
  bool false_detection = false;  ///< flagged while no fault was in force on it
};

class FaultBook {
 public:
  /// A flag raised within grace_s after a fault's clear is that fault's (a late detection).
  FaultBook(int per_side, std::vector<AgentFaultEvent> events, double grace_s = 0.0);

  /// Applies the events of tick k (time t_s).
  void apply(long long k, double t_s);
  /// The motor faults in force on a side (index: agent).
  const std::vector<model::MotorFault>& motor(int side) const { return motor_[side]; }
  /// True when a side has a motor fault in force.
  bool any_motor_fault(int side) const;
  /// The group of `side` announced these flags (0: healthy, else the diagnosis' code; names:
  /// `names[code]`) in its status of time t_s; the flagged agents are disconnected.
  void on_flags(int side, const std::vector<uint8_t>& flags, double t_s, double dt_s,
                const char* const* names, int n_names);
  bool disconnected(int side, int index) const;
  /// The fault in force on agent `index` of `side` acted on the drive over the tick held.
  void exposed(int side, int index);

  const std::vector<AgentFaultRecord>& records() const { return records_; }
  const std::vector<DiagnosisEvent>& events() const { return events_; }
  int false_detections() const { return false_; }

 private:
  int per_side_;
  double grace_s_;
  std::vector<AgentFaultEvent> events_in_;
  std::size_t next_ = 0;
  std::vector<model::MotorFault> motor_[2];
  std::vector<int> open_[2];  ///< per agent: the record of the fault in force, -1 if none
  std::vector<int> last_[2];  ///< per agent: its latest record, -1 if none
  std::vector<uint8_t> flags_[2];
  std::vector<AgentFaultRecord> records_;
  std::vector<DiagnosisEvent> events_;
  int false_ = 0;
};

}  // namespace maptr::plant_core
