#pragma once
// The fleet view of `maptr top`: folds the samples of a fleet's topics into what the screen
// shows. Pure: no DDS participant, no clock, no terminal. Every sample comes with the time it
// arrived (s, on any steady clock the caller keeps), and `observe(now_s)` tells the view what time
// it is, so the tick statistics and the "paused" state follow only from the numbers given.
//
//   real-time factor  = (t_last - t_first) / (arrival_last - arrival_first) over the last
//                       kRateWindowTicks ticks (simulated s per wall s)
//   tick interval     = arrival_k - arrival_{k-1} for consecutive tick indices (ms); median and p99
//   speed error       = 100 (v_x - v_x_ref) / |v_x_ref|  (%), v_x_ref: central's last command
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "control/level2/status.hpp"
#include "idl/maptr.h"

namespace maptr::top {

/// Ticks the real-time factor and the tick statistics are computed over.
inline constexpr std::size_t kRateWindowTicks = 500;
/// Membership and fault events the view keeps (all of a run's; a bound against a flood).
inline constexpr std::size_t kEventsKept = 100000;
/// A live agent whose last reply is older than this (wall s) while the view watches is paused.
inline constexpr double kPausedAfter_s = 1.0;
/// A group whose last status is this many ticks behind the plant's tick is shown silent.
inline constexpr long long kGroupSilentTicks = 50;

/// What one agent does, as the view shows it.
enum class CellState { kUnknown, kActive, kIdle, kHolding, kCoasting, kStopping, kDead, kPaused, kRejoining, kFaulty };

/// "active", "idle", ..., "rejoining", "faulty" (alive, isolated by its group); "?" for kUnknown.
const char* state_name(CellState s);
/// One letter per state for the compact view (A active, . idle, H, C, S, X dead, P, R, F faulty, ?).
char state_letter(CellState s);

/// One agent: its last reply, its wear from its group, what the launcher and the plant said.
struct AgentCell {
  msg::AgentState reply_state = msg::AGENT_IDLE;
  long long reply_tick = -1;     ///< tick of the last reply, -1 none
  double reply_arrival_s = 0.0;  ///< arrival of the last reply
  double voltage_V = 0.0;        ///< V applied
  double current_A = 0.0;        ///< A drawn
  double wear_m = 0.0;           ///< m driven while active (Level-3 ledger)
  bool live = true;              ///< the plant's live mask
  bool died = false;             ///< the launcher said it died (and no start since)
  bool rejoining = false;        ///< started again, not yet back in the plant's live mask
  uint8_t faulty = 0;            ///< its group's flag (msg::FaultDiagnosis): isolated though alive
};

/// One side: the plant's battery and wheel, the group's Level-2/Level-3 status, its agents.
struct SideView {
  double battery_V = 0.0, discharge_mAh = 0.0;  ///< V, mAh
  double phidot = 0.0, phidot_ref = 0.0;        ///< rad/s
  int n_active = 0;                             ///< active in the plant's tick
  bool group_heard = false;                     ///< a GroupStatus arrived
  long long group_tick = -1;                    ///< tick of the last GroupStatus
  bool group_died = false;                      ///< the launcher said the group died
  control::Level2Decision level2;  ///< the group's last Level-2 decision, as its status carries it
  int group_n_active = 0, group_n_live = 0;
  uint64_t decisions = 0, reallocations = 0;
  std::vector<AgentCell> agents;
};

/// One line of the event log.
struct ViewEvent {
  double t_s = 0.0;  ///< simulated time, s (of the last tick seen when it arrived); NaN: not known
  std::string text;
};

/// Where the run is.
enum class Phase { kWaiting, kRunning, kFinished, kAborted, kGone };
const char* phase_name(Phase p);

/// What the fleet's coordinates say before any sample arrives.
struct RunInfo {
  std::string scenario;    ///< scenario name
  std::string run_dir;     ///< run folder
  int agents = 0;          ///< fleet size
  double duration_s = 0;   ///< simulated s
  int domain = 0;          ///< DDS domain
  double replay_rate = 0;  ///< > 0: a replay of the run's recording at this many times its pace
};

/// Median and 99th percentile of the tick intervals, ms; n intervals (0: none yet).
struct TickStats {
  double median_ms = 0.0, p99_ms = 0.0;
  std::size_t n = 0;
};

class FleetView {
 public:
  explicit FleetView(RunInfo info);

  void on_tick(const msg::PlantTick& t, double arrival_s);
  void on_reply(const msg::AgentReply& r, double arrival_s);
  void on_group(const msg::GroupStatus& g);
  void on_central(const msg::CentralCommand& c);
  /// before_join: written before the watcher joined (its time is not known).
  void on_membership(const msg::MembershipEvent& e, bool before_join = false);
  void on_gate(const msg::FaultGate& g);
  /// What the scenario schedules at each fault gate's tick ("kill of L3, restart of L1"), so
  /// that a gate's event names its faults.
  void set_gate_faults(std::map<long long, std::string> by_tick) { gate_faults_ = std::move(by_tick); }
  /// A replay: the run's own record of its events (summary.json), in simulated-time order. They
  /// enter the log as the replayed ticks reach their time (all of them at the run's end); the
  /// membership events and gates that come over DDS then change the cells only.
  void set_recorded_events(std::vector<ViewEvent> events);
  void on_ready(const msg::NodeReady& r);
  /// The run's summary.json: its status and end reason (the fleet has ended).
  void on_summary(const std::string& status, const std::string& end_reason);
  /// The fleet ended without a final tick (its launcher is gone).
  void on_fleet_gone();
  /// The current time (same clock as the arrivals).
  void observe(double now_s) { now_s_ = now_s; }

  const RunInfo& info() const { return info_; }
  Phase phase() const { return phase_; }
  bool ticked() const { return tick_ >= 0; }
  long long tick() const { return tick_; }
  double t_s() const { return t_s_; }
  double v_x() const { return v_x_; }
  double v_x_ref() const { return v_x_ref_; }
  double yaw_rate() const { return w_; }
  double energy_J() const { return energy_J_; }
  double distance_m() const { return distance_m_; }
  int ready_nodes() const { return static_cast<int>(ready_.size()); }
  const SideView& side(int s) const { return sides_[s]; }
  const std::deque<ViewEvent>& events() const { return events_; }
  const std::string& final_status() const { return final_status_; }
  const std::string& end_reason() const { return end_reason_; }

  /// Simulated s per wall s over the last ticks; 0 before two ticks.
  double real_time_factor() const;
  TickStats tick_stats() const;
  /// 100 (v_x - v_x_ref) / |v_x_ref|; 0 while the reference is 0.
  double speed_error_pct() const;
  /// The state the view shows for agent `index` of side `s`.
  CellState state(int s, int index) const;
  int count(CellState st) const;
  /// Agents that are neither dead nor rejoining.
  int live_agents() const;
  /// A group heard, not dead and not far behind the plant's tick.
  bool group_silent(int s) const;

 private:
  struct Arrival {
    long long tick;
    double t_s, arrival_s;
  };
  void add_event(const std::string& text, double t_s);
  /// The recorded events up to simulated time t (all of them with t = +inf).
  void release_recorded(double t);
  AgentCell* cell(int side, int index);
  void fold_side(int s, const msg::SideTick& st);

  RunInfo info_;
  Phase phase_ = Phase::kWaiting;
  long long tick_ = -1;
  double t_s_ = 0.0, v_x_ = 0.0, v_x_ref_ = 0.0, w_ = 0.0, energy_J_ = 0.0, distance_m_ = 0.0;
  double now_s_ = 0.0;
  SideView sides_[2];
  std::deque<Arrival> arrivals_;
  std::deque<ViewEvent> events_;
  std::map<long long, std::string> gate_faults_;
  bool recorded_ = false;               ///< events come from set_recorded_events()
  std::deque<ViewEvent> recorded_events_;  ///< not yet reached
  std::vector<std::string> ready_;
  std::string final_status_, end_reason_;
};

}  // namespace maptr::top
