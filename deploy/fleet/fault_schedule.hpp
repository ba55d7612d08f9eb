#pragma once
// Fault injection, free of DDS and processes:
//   - a random fault schedule reproducible from a seed (--chaos SEED);
//   - the scenario's scheduled faults in time order: those due at a fault gate of the plant
//     (the first tick at or after their time), and the record of every fault applied or
//     skipped (the summary's "failures": {target, action, at_s, wall_ms[, skipped]});
//   - what applying a fault means for its target in its present state.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/scenario.hpp"

namespace maptr::deploy {

/// What a random fault schedule may contain.
struct ChaosOptions {
  int outages = 4;  ///< outages drawn (those overlapping an earlier one of the same target are dropped)
  double pause_share = 1.0 / 3.0;  ///< share of the outages that are pauses instead of kills
  bool discovery = false;          ///< the discovery server is a target too
  int agent_faults = 1;            ///< agents broken while they run on (a fault, cleared 2-8 s later)
};

/// Outages of agents and controllers (never the plant) at random simulated times, the same for
/// the same seed, scenario and options: a kill restarted 2-8 s later, or a pause resumed 2-8 s
/// later; the discovery server is only killed (the launcher restarts it). On several hosts, one
/// host other than h0 is also cut off and healed 2-8 s later. Then `agent_faults` agents break
/// while they run on, each in a mode drawn from all eight (docs/ARCHITECTURE.md "Fault
/// detection"), and are mended 2-8 s later; drawn from a stream of their own, so that the
/// outages stay those of a schedule without them.
std::vector<config::FaultSpec> chaos_schedule(unsigned seed, const config::Scenario& s,
                                              const ChaosOptions& o);
/// The schedule of `--chaos SEED`: `faults` outages, a third of them pauses.
std::vector<config::FaultSpec> chaos_schedule(unsigned seed, const config::Scenario& s, int faults = 4);

namespace fleet {

/// Name under which the discovery server is a fault target.
inline constexpr const char* kDiscoveryTarget = "discovery";

/// A fault target's state when a fault is applied to it.
struct TargetState {
  bool known = false;     ///< a process of the fleet (or the discovery server)
  bool external = false;  ///< started by the user, not the launcher's to kill or start
  bool running = false;
  bool paused = false;  ///< stopped by a pause fault (SIGSTOP), not resumed yet
  bool remote = false;  ///< started over ssh: the launcher's pid is its ssh client
};

/// What the launcher does for a fault: kill, start, pause (SIGSTOP) or resume (SIGCONT) its
/// target, or skip it (and why).
struct FaultAction {
  enum Kind { kKill, kRestart, kPause, kResume, kSkip } kind = kSkip;
  std::string skipped;  ///< why it is skipped ("" unless kSkip)
};

/// The rule: a running target is killed (paused or not), a dead one restarted, a running one
/// paused, a paused one resumed; the discovery server is never restarted by a fault (the
/// launcher restarts it by itself); external processes are left alone.
FaultAction decide_fault(const config::FaultSpec& f, const TargetState& s);

/// The faults the launcher applies: all but the agents' own (fault, clear), which the plant and
/// the agents apply at their tick and the plant records.
std::vector<config::FaultSpec> launcher_faults(const std::vector<config::FaultSpec>& faults);

/// The scheduled faults of a run, in time order, and the record of every fault.
class FaultSchedule {
 public:
  explicit FaultSchedule(std::vector<config::FaultSpec> faults);  ///< stable-sorted by at_s

  /// Takes out every scheduled fault due at a gate of simulated time gate_t (at_s <= gate_t).
  std::vector<config::FaultSpec> due(double gate_t);
  /// Records a fault applied at simulated time at_s (wall clock wall_ms, ms since the epoch);
  /// origin says who asked for it ("scheduled", "chaos", "command").
  void record(const config::FaultSpec& f, double at_s, double wall_ms, const FaultAction& a,
              const std::string& origin = "scheduled");
  /// Adds key = value to the last record.
  void annotate_last(const std::string& key, const nlohmann::json& value) { records_.back()[key] = value; }
  /// The run ended: every fault not yet due is recorded as skipped.
  void close();

  const nlohmann::json& records() const { return records_; }

 private:
  std::vector<config::FaultSpec> faults_;
  std::size_t next_ = 0;
  nlohmann::json records_ = nlohmann::json::array();
};

}  // namespace fleet
}  // namespace maptr::deploy
