#pragma once
// The plant's lock-step loop: its DDS endpoints and the protocol objects they feed (membership,
// barrier, validation, fault gate, report). PlantNode::run() drives it: discover, then per tick
// gate, publish, collect, integrate, pace; then report. Set-up, discovery, gates, publishing and
// membership are in plant_loop.cpp; taking samples, integrating, pacing and the report in
// plant_intake.cpp.
#include <spdlog/logger.h>

#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "comm/dds/discard.hpp"
#include "comm/dds/process.hpp"
#include "comm/lockstep/tick_filter.hpp"
#include "idl/maptrPubSubTypes.h"
#include "plant/barrier.hpp"
#include "plant/discovery_wait.hpp"
#include "plant/fault_gate.hpp"
#include "plant/ledger_keeper.hpp"
#include "plant/membership.hpp"
#include "plant/plant_config.hpp"
#include "plant/run_outcome.hpp"
#include "plant/tick_records.hpp"
#include "plant/validation.hpp"
#include "plant/wear_watch.hpp"
#include "plant_core/plant_core.hpp"

namespace maptr::plant {

using Clock = std::chrono::steady_clock;
using Handle = eprosima::fastrtps::rtps::InstanceHandle_t;

/// The membership's DDS-free id of a writer (its GUID bytes).
inline WriterId writer_id(const Handle& h) {
  WriterId w;
  const eprosima::fastrtps::rtps::octet* p = h.value;
  std::copy(p, p + w.bytes.size(), w.bytes.begin());
  w.set = h.value.has_been_set();
  return w;
}

/// Microseconds from a to b.
inline float us(Clock::time_point a, Clock::time_point b) {
  return static_cast<float>(std::chrono::duration<double, std::micro>(b - a).count());
}

/// groups' assignments and central's references (carried in the next Tick).
struct Commands {
  std::vector<plant_core::AgentApplied> applied[2];
  std::vector<uint8_t> mask[2];
  long long group_stamp[2] = {-1, -1};
  long long central_stamp = -1;
  double ref[2] = {0.0, 0.0};  ///< rad/s, wheel references per side
  int relay[2] = {0, 0};       ///< the other side's active count, relayed to each side
};

/// Wall-clock instants of one lock-step tick.
struct TickTimes {
  Clock::time_point publish, start, first_reply, complete, done;
  TickNote note;  ///< reset when the barrier starts
};

/// A seam for the tests' hooked plant (tests/hooks): its discovery does not count the first start
/// of agent `name`'s answer writer, as if the discovery server had dropped that endpoint (seen
/// with 512 agents). The product installs none.
void hide_first_answer_writer_of(const std::string& name);

/// The plant's DDS endpoints and the protocol objects they feed.
class PlantLoop {
 public:
  PlantLoop(const comm::ProcessArgs& args, spdlog::logger& log, const PlantNodeConfig& c);

  bool discover();
  /// What the calling thread, the lock-step thread, runs under (comm::make_thread_realtime):
  /// logged and kept for plant.json.
  void set_scheduling(std::string what);
  void open_records();
  /// True when the current tick is the last one to publish (duration reached or speed lost);
  /// stamps the membership records with its time and notes why the run ends.
  bool last_tick();
  void pass_gate();
  void publish(msg::RunState run_state);
  /// Waits until tick k is complete; false on the stop signal.
  bool collect();
  void integrate();
  void pace();
  int report(bool stopped);

 private:
  void wait_gate(long long k);
  void apply_launcher_events();
  void apply_liveliness();
  void take_replies(long long k, const SampleLimits& lim);
  void take_groups(long long k, const SampleLimits& lim);
  void take_centrals(long long k, const SampleLimits& lim);
  SampleLimits limits() const;
  void log_membership();
  /// True when `writer` belongs to the process whose first participant id is `base_id`
  /// (comm/dds/fleet_ids.hpp) in this fleet; always, without a fleet id.
  bool sent_by(const Handle& writer, int base_id) const;
  /// What the plant has matched so far, naming the members it has not (plant/discovery_wait.hpp).
  DiscoveryView discovery_view(int tick_readers) const;
  /// The matched answer writers the test seam hides (hide_first_answer_writer_of); 0 without it.
  int hidden_replies() const;
  /// Samples dropped by each process: the plant's own and what each follower last reported.
  std::map<std::string, uint64_t> rejects_by_process() const;
  /// Samples the plant itself dropped (checks failed, or a payload that did not deserialize).
  uint64_t own_rejects() const;
  void wait(std::chrono::milliseconds at_most);
  /// Writes the plant's hello (topic::kHello) to its `members` readers and logs how long it took.
  void say_hello(int members);
  /// Sleeps until every late member's answer may have arrived (one wake-up, not one per sample),
  /// a membership event, or `at_most`.
  void wait_for_answers(uint64_t seen, std::chrono::milliseconds at_most);
  double now_s() const { return std::chrono::duration<double>(Clock::now() - origin_).count(); }

  const config::Scenario& sc_;
  const std::string run_dir_;
  spdlog::logger& log_;
  const PlantNodeConfig c_;
  const int per_side_;
  std::atomic<bool>& stop_;
  const Clock::time_point origin_ = Clock::now();

  comm::Signal signal_;
  comm::Inbox<msg::AgentReply> replies_{signal_, comm::Wake::kCounted};
  comm::Inbox<msg::GroupStatus> groups_{signal_, comm::Wake::kCounted};
  comm::Inbox<msg::CentralCommand> centrals_{signal_, comm::Wake::kCounted};
  comm::Inbox<msg::MembershipEvent> members_{signal_};
  comm::Inbox<msg::Control> controls_{signal_};
  /// Keeps the tick writer's writes apart from Fast DDS's changes of its filter table (declared
  /// before the participant, whose end still deletes filters through it).
  comm::TickFilterGate filter_gate_;
  comm::TickWriterMatch tick_match_{&signal_, &filter_gate_};
  comm::MatchCounter hello_match_;
  comm::Discard<msg::NodeReady> readies_;  ///< read so that each member's ready opens this port
  comm::Participant p_;
  eprosima::fastdds::dds::DataWriter* w_tick_ = nullptr;
  eprosima::fastdds::dds::DataWriter* w_ready_ = nullptr;
  eprosima::fastdds::dds::DataWriter* w_hello_ = nullptr;
  eprosima::fastdds::dds::DataWriter* w_gate_ = nullptr;
  uint64_t seen_ = 0;
  uint64_t consumed_ = 0;  ///< lock-step samples taken from the counted inboxes so far

  plant_core::PlantCore core_;
  std::unique_ptr<RunFiles> files_;
  Membership membership_;
  std::size_t logged_records_ = 0;
  FaultGate gate_;
  Barrier barrier_;
  Commands cmd_;
  msg::PlantTick sent_;  ///< the tick last published (resent unchanged to a restarted member)
  /// Each side's speed and reference of the tick published before sent_ (SideTick::phidot_prev).
  double prev_phidot_[2] = {0.0, 0.0}, prev_ref_[2] = {0.0, 0.0};
  long long published_tick_ = -1;  ///< sent_'s tick, -1 before the first
  /// Sets each side's wake mask of sent_ (SideTick::wake): assigned, idle slot due or rejoining.
  void set_wake();
  /// Fills a side's drive measurements of the tick last integrated (fault detection).
  void put_measurements(msg::SideTick& side, int s);
  /// Logs the agents a group isolates or lets back (before the core takes its flags).
  void log_diagnoses(int side, const std::vector<uint8_t>& flags);
  static const char* const* diagnosis_names();
  /// Writes sent_ on the tick writer (through the filter gate).
  void write_tick() {
    filter_gate_.write([this] { w_tick_->write(&sent_); });
  }
  TickTimes times_;
  TickTiming timing_;
  Clock::time_point last_publish_{};  ///< of the tick before (the period between two publishes)
  Clock::time_point wall0_;
  std::string end_reason_ = "duration reached";
  uint64_t rejected_ = 0, missed_deadlines_ = 0, declared_dead_ = 0;
  std::string scheduling_ = "normal";  ///< what the lock-step thread runs under
  uint64_t late_ = 0;  ///< answers from their own sender to a tick before k - 1 (validation.hpp late())
  /// The first this many rejected (and late) samples are logged one by one.
  static constexpr uint64_t kRejectsLogged = 20;
  /// Whether an answer to tick k is used. A copy of the answer to tick k - 1 from its own sender
  /// is skipped, an older one from its own sender counted as late, anything else not accepted or
  /// not from its own sender counted as rejected; the first kRejectsLogged of each are logged.
  bool admit(Verdict v, bool own, unsigned long long tick, long long k, const char* what, int side, int index);
  uint64_t taken_[3] = {0, 0, 0};     ///< answers used: agents', groups', central's
  /// Whether an admitted answer is its writer's first for tick k (OncePerTick); a conflicting
  /// one is counted and logged.
  bool once(Once o, const char* what, int side, int index, long long k);
  /// Counts a dropped sample of `kind` (malformed, forged, stale, conflicting, ...); returns
  /// how many the plant has dropped.
  uint64_t reject(const char* kind);
  /// A controller's sample from its one writer since its last start (else rejected and counted).
  bool one_writer(const MemberId& id, const Handle& h, long long k);
  /// Control samples: taken only from the launcher and well-formed; the others counted.
  std::vector<msg::Control> take_controls();
  std::map<std::string, uint64_t> kinds_;  ///< dropped samples by kind (plant.json rejected_by_kind)
  std::vector<OncePerTick<msg::AgentReply>> once_reply_[2];
  OncePerTick<msg::GroupStatus> once_group_[2];
  OncePerTick<msg::CentralCommand> once_central_;
  uint64_t repairs_ = 0;              ///< ticks sent again because answers were missing
  double barrier_average_s_ = 0.0;    ///< typical barrier time (exponential average), s
  /// What each follower last said it dropped (its `rejected` field).
  std::vector<uint64_t> agent_rejects_[2];
  uint64_t group_rejects_[2] = {0, 0}, central_rejects_ = 0;
  WearWatch wear_;  ///< the groups' ledgers, never to go backwards
  LedgerKeeper ledgers_;  ///< the groups' last ledgers, for a restart and ledger-<side>.json
};

}  // namespace maptr::plant
