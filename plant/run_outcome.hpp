#pragma once
// The run's report: its status (ok, degraded or aborted, with the reason), the wall-clock
// timing of the lock-step ticks and the content of plant.json (records/plant_results.hpp).
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "plant/membership.hpp"
#include "plant_core/plant_core.hpp"
#include "records/plant_results.hpp"

namespace maptr::plant {

/// What a tick's wall time may owe to: which kind of process answered last, whether the plant
/// wrote a trace row, whether a group's Level-2 solve was under way when it answered.
struct TickNote {
  enum Last : int8_t { kNone = -1, kAgent = 0, kGroup = 1, kCentral = 2 };
  long long tick = -1;        ///< k
  int8_t last = kNone;        ///< the kind of the last answer the barrier took
  bool traced = false;        ///< the tick's trace row was written
  bool level2_solving = false;
};

/// Wall-clock cost of each lock-step tick, µs: publishing, the first reply, the whole barrier,
/// the integration, the tick from publish to integrated, and the period from one publish to the
/// next (what a tick costs the run's wall time: the real-time factor is 1 / mean period at the
/// tick's step). The slowest 1 % of the ticks (by `tick`) are told apart by their TickNote.
class TickTiming {
 public:
  /// first_reply_us < 0: no reply came in during the tick.
  void add(float publish_us, float first_reply_us, float barrier_us, float integrate_us, float tick_us,
           TickNote note);
  void add_period(float period_us) { period_.push_back(period_us); }
  /// {"publish", "first_reply", "barrier", "integrate", "tick", "period"}: each {median, mean, p90,
  /// p99, max, n}, or an empty object when nothing was measured; "slowest_1pct": what the
  /// slowest 1 % of the ticks have in common, each share beside the same share over all ticks,
  /// and the five slowest ticks (k, µs and the part that took longest).
  nlohmann::json json() const;

 private:
  nlohmann::json slowest() const;
  std::vector<float> publish_, first_reply_, barrier_, integrate_, tick_, period_;
  std::vector<TickNote> notes_;  ///< one per tick_
  /// The five slowest ticks, slowest first: index into tick_ (and the other parts).
  nlohmann::json five_slowest(const std::vector<std::size_t>& order) const;
};

/// Median, mean, p90, p99 (nearest rank below), max and n of a series; an empty object when empty.
nlohmann::json quantiles(std::vector<float> v);

/// How the run ended, as the node saw it.
struct RunEnd {
  bool stopped = false;            ///< the stop signal ended the loop
  int live_agents[2] = {0, 0};     ///< live agents per side at the end
  bool reached_reference = false;  ///< the speed reached its reference at least once
  bool speed_lost = false;
  double ref_speed_mps = 0.0;  ///< final body speed reference, m/s
  double speed_mps = 0.0;      ///< final body speed, m/s
  /// Controllers ("central", "group-L", "group-R") dead or paused at the end: their agents were
  /// left to their own safe behaviour (a ramp to a stop without central; hold, then coast,
  /// without their group).
  std::vector<std::string> silent_controllers;
  double cross_track_max_m = 0.0;    ///< largest |cross-track error| after the first second, m
  double cross_track_max_t_s = 0.0;  ///< when it was, s
  double path_tolerance_m = 0.0;     ///< above this the path was not followed (0: not judged)
  /// With fault detection on: the agents' faults left undetected, and the false detections
  /// (fault_problems(), in words).
  std::vector<std::string> fault_problems;
};

/// What the fault record says went wrong: each injected fault its group never flagged ("fault
/// sensor=5 on L3 at 20.00 s not detected") and each flag raised on an agent with no fault in
/// force ("L3 isolated at 12.30 s as short with no fault in force (a false detection)").
/// A fault counts as undetected only once it acted on the drive for more than
/// `exposed_ticks_needed` ticks (twice the persistence time: a fault on an agent that never
/// drove while it was in force cannot be seen, and did no harm).
std::vector<std::string> fault_problems(const plant_core::FaultBook& book, long long exposed_ticks_needed);

/// "ok", "aborted: stop signal", or "degraded: ..." when a side has no live agent, a controller
/// was dead or paused at the end, an agent's fault went undetected or a healthy one was
/// isolated (with detection on), the path was not followed (cross-track error above the
/// tolerance), or the run ended more than degraded_band_pct off its reference speed (a run that
/// never reached its speed, or that ended for a lost speed, is not judged on it).
std::string run_status(const RunEnd& e, double degraded_band_pct);
bool aborted(const std::string& status);

/// "duration reached", or why the run ended early for a lost speed.
std::string end_reason(bool speed_lost, double stop_below_speed_pct, double hold_s, double t_s);

/// Everything plant.json holds besides the core's ledgers.
struct ReportInputs {
  std::string status;
  std::string end_reason;
  double tick_hz = 0.0;
  double loop_wall_s = 0.0;
  int live_agents[2] = {0, 0};
  uint64_t rejected_samples = 0;
  /// Samples each process dropped (the plant's own, and what each follower last reported).
  std::map<std::string, uint64_t> rejected_by_process;
  /// The plant's own drops by kind (malformed, forged, other_tick, conflicting, stale,
  /// undecodable) and its late answers (late).
  std::map<std::string, uint64_t> rejected_by_kind;
  /// Answers from their rightful sender that came after the plant had gone past the next tick:
  /// not used, and not counted among the rejected (which are malformed or forged).
  uint64_t late_samples = 0;
  uint64_t missed_deadlines = 0;
  std::string loop_scheduling = "normal";  ///< what the lock-step thread ran under
  uint64_t tick_repairs = 0;  ///< ticks sent again because answers were missing (lost samples)
  /// Answers the plant used, by topic (each answers one tick of one member once).
  std::map<std::string, uint64_t> answers_taken;
  uint64_t declared_dead_by_deadline = 0;
  nlohmann::json tick_timing_us = nlohmann::json::object();
  nlohmann::json group_wear = nlohmann::json::object();  ///< WearWatch::json()
};

/// The content of plant.json (records/plant_results.hpp).
records::PlantResults plant_results(const plant_core::PlantCore& core, const ReportInputs& in,
                                    const std::vector<MembershipRecord>& records);

}  // namespace maptr::plant
