#pragma once
// The launcher's stall watchdog: a run whose plant publishes no new tick and no fault gate for
// `limit_s` of wall time has stalled (every process starved or blocked, e.g. all of them losing
// their DDS leases at once), and the launcher ends it with a status that says so instead of
// waiting forever. Progress is counted in simulated terms (a tick or gate with a later
// simulated time, or a new gate); wall times are passed in explicitly (s since any origin).
#include <string>

namespace maptr::deploy::fleet {

class StallWatch {
 public:
  /// limit_s: wall time without progress after which the run has stalled, s (> 0).
  explicit StallWatch(double limit_s) : limit_s_(limit_s) {}

  /// The run starts at wall time now_s (the plant was told to start).
  void start(double now_s);
  /// The plant's clock reads t_sim_s (s) after `gates` fault gates, at wall time now_s: a
  /// later simulated time or a new gate is progress.
  void observe(double t_sim_s, long gates, double now_s);
  /// The launcher itself held the run until now_s (a fault gate it was answering): not a stall.
  void held_until(double now_s) { last_progress_s_ = now_s; }
  /// True when the run started and made no progress for more than the limit at now_s.
  bool stalled(double now_s) const { return started_ && now_s - last_progress_s_ > limit_s_; }
  /// Wall time since the last progress at now_s, s.
  double idle_s(double now_s) const { return now_s - last_progress_s_; }
  double last_t_sim_s() const { return t_sim_s_; }
  double limit_s() const { return limit_s_; }

 private:
  double limit_s_;
  bool started_ = false;
  double last_progress_s_ = 0.0;
  double t_sim_s_ = -1.0;
  long gates_ = 0;
};

/// The status of a stalled run: "aborted: stalled: ...", with the limit and the last simulated time.
std::string stalled_status(const StallWatch& w);

}  // namespace maptr::deploy::fleet
