#pragma once
// The loop every process that follows the plant's ticks runs (agents, groups, central): it
// reads PlantTick, answers on one writer, announces readiness once both are matched, and ends
// when the run ends (0), when the plant is lost through DDS liveliness (3) or on SIGTERM/SIGINT
// (0). The node only says what to answer. A tick counts only if the plant's writer sent it
// (its fleet GUID prefix; without a fleet id, the first writer heard) and it is newer than the
// last one; a jump forward is a resynchronisation (after a pause or a restart); an exact copy
// of the last tick (the plant resends it to a restarted member) is ignored; a tick whose
// `paused` mask marks this process (the launcher paused it at a fault gate; it reads the ticks
// it missed once resumed) is skipped without an answer, so that a resumed process acts first on
// the tick of its resume gate, as in every run; every other tick (malformed, stale, from
// another writer) is dropped and counted.
#include <spdlog/logger.h>

#include <atomic>
#include <functional>
#include <memory>
#include <optional>

#include "comm/dds/discard.hpp"
#include "comm/dds/process.hpp"
#include "comm/lockstep/tick_check.hpp"
#include "idl/maptrPubSubTypes.h"

namespace maptr::comm {

/// A process's entry in PlantTick::paused: agents L0.., R0.., then group-L, group-R, central;
/// -1 for any other name.
int paused_slot(const std::string& name, int per_side);

/// True when the tick marks the process of slot `slot` as paused.
bool paused_in(const msg::PlantTick& t, int slot);

class TickFollower {
 public:
  TickFollower(const ProcessArgs& args, msg::NodeKind node_kind, std::shared_ptr<spdlog::logger> log);

  /// Creates the writer this process answers each tick on (readiness waits for its match).
  template <class PubSubType>
  eprosima::fastdds::dds::DataWriter* answer_writer(const char* topic_name) {
    answer_ =
        participant_->writer(participant_->topic<PubSubType>(topic_name), Profile::kStream, &answer_match_);
    return answer_;
  }

  /// Sends this tick's answer on the answer writer, and keeps it: a repeated tick (the plant
  /// resends a tick whose answers did not all arrive) is answered again with the same sample.
  template <class Msg>
  void answer(const Msg& m) {
    // A follower answers with one message type: the kept copy is made once and then assigned.
    auto* kept = static_cast<Msg*>(last_answer_.get());
    if (!kept) {
      auto first = std::make_shared<Msg>(m);
      kept = first.get();
      last_answer_ = std::move(first);
      resend_ = [this, kept]() { answer_->write(kept); };
    } else {
      *kept = m;
    }
    answered_tick_ = last_tick_;
    resend_();
  }

  /// Calls on_tick for each valid new tick of the running run; returns the exit code.
  int run(const std::function<void(const msg::PlantTick&)>& on_tick);

  /// Ticks dropped as malformed, stale, undecodable or not from the plant so far.
  uint64_t rejected() const { return rejected_.load() + ticks_.undecodable(); }

 private:
  const ProcessArgs& args_;
  msg::NodeKind kind_;
  std::shared_ptr<spdlog::logger> log_;
  // Listeners first: they must outlive the participant that calls them.
  Signal signal_;
  Direct<msg::PlantTick> ticks_{signal_};
  Discard<msg::NodeReady> hello_;
  MatchCounter answer_match_{&signal_};
  std::unique_ptr<Participant> participant_;
  eprosima::fastdds::dds::DataWriter* ready_ = nullptr;
  eprosima::fastdds::dds::DataWriter* answer_ = nullptr;
  std::atomic<uint64_t> rejected_{0};
  std::shared_ptr<void> last_answer_;
  long long answered_tick_ = -1;  ///< the tick last_answer_ answers
  std::function<void()> resend_;
  std::atomic<uint64_t> skipped_paused_{0};
  std::atomic<uint64_t> followed_{0};  ///< ticks handed to the node (an agent's: the tick filter's)
  int slot_ = -1;                      ///< this process's entry in PlantTick::paused (paused_slot)
  std::optional<eprosima::fastrtps::rtps::InstanceHandle_t> plant_writer_;
  // Written on the DDS receive thread by on_sample, read by the loop.
  long long last_tick_ = -1;
  std::atomic<bool> heard_{false};     ///< a tick came since the loop last looked
  std::atomic<bool> finished_{false};  ///< the run ended (a tick not RUN_RUNNING)

  bool from_plant(const eprosima::fastrtps::rtps::InstanceHandle_t& writer);
  /// One tick sample, on the DDS receive thread.
  void on_sample(const msg::PlantTick& t, const eprosima::fastrtps::rtps::InstanceHandle_t& writer,
                 const std::function<void(const msg::PlantTick&)>& on_tick);
};

}  // namespace maptr::comm
