#pragma once
// The fault gate: the plant holds the first tick at or after each scheduled fault until the
// launcher answers CONTROL_GATE_OPEN for that tick and the plant has applied every membership
// event the launcher published before its answer (member_seq), so that a fault acts at the
// same tick in every run. Times are explicit: simulated time for the schedule, elapsed wall
// time for the timeout.
#include <cstdint>
#include <vector>

namespace maptr::plant {

class FaultGate {
 public:
  /// fault_times_s: simulated times of the scheduled faults, s (any order, repeats allowed);
  /// timeout_s: wall time after which a gate is given up, s.
  FaultGate(std::vector<double> fault_times_s, double timeout_s);

  /// Distinct gate times, ascending, s.
  const std::vector<double>& times() const { return times_; }
  /// True when the tick at simulated time t_s must be held: the first tick at or after one or
  /// more gate times not yet passed (all of them are consumed).
  bool due(double t_s);

  /// Holding tick k from now on.
  void hold(uint64_t tick);
  /// The launcher's CONTROL_GATE_OPEN for `tick`, sent after member_seq membership events
  /// (an answer for another tick is ignored).
  void on_open(uint64_t tick, uint64_t member_seq);
  /// True when the held tick may go: the launcher answered and every membership event it
  /// published before (up to applied_seq) has been applied.
  bool released(uint64_t applied_seq) const { return open_ && applied_seq >= need_seq_; }
  /// True when the wait has lasted longer than the timeout.
  bool timed_out(double waited_s) const { return waited_s > timeout_s_; }
  double timeout_s() const { return timeout_s_; }

 private:
  std::vector<double> times_;
  std::size_t next_ = 0;
  double timeout_s_;
  uint64_t tick_ = 0;
  bool open_ = false;
  uint64_t need_seq_ = 0;
};

}  // namespace maptr::plant
