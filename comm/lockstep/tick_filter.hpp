#pragma once
// The tick filter: a Fast DDS content filter (IContentFilterFactory) that lets an agent take
// only the ticks comm::tick_wakes_agent says it needs. Registered on the plant's participant,
// whose tick writer then evaluates it for each agent's reader before sending (writer-side
// filtering: an idle agent is not woken at all for the nine ticks in ten it does not answer),
// and on each agent's participant, whose reader evaluates it for samples the writer did not
// filter. A tick that does not decode is delivered: the follower's checks then reject it.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/topic/ContentFilteredTopic.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <mutex>

#include "comm/dds/dds.hpp"

namespace maptr::comm {

/// The filter class name both sides register.
inline constexpr const char* kTickFilterClass = "MAPTR_TICK_WAKE";

/// Keeps the tick writer's writes apart from changes of its table of reader filters. Fast DDS
/// 2.9.1 adds a reader's filter to that table, or removes it (an agent started or gone), on its
/// discovery thread without the writer's lock (StatelessWriter::matched_reader_add/remove call
/// the listener after unlocking), while write() walks the table evaluating every filter; the
/// fix came in Fast DDS 3.0 for removals only. Each change calls the filter factory first (a new
/// filter, or the deletion of one) and the writer's publication-matched listener after, on the
/// same thread: the factory calls mutation_begins(), which waits until no write is under way and
/// holds later writes back until the listener calls matched_changed().
class TickFilterGate {
 public:
  /// A filter is about to enter or leave the writer's table (discovery thread).
  void mutation_begins();
  /// The writer's matched readers changed: the table change that preceded it is done.
  void matched_changed();
  /// Writes through `write` once no table change is pending; after `limit`, writes anyway and
  /// counts it in timeouts() (a change whose listener call never came).
  template <class F>
  void write(F&& write, std::chrono::milliseconds limit = std::chrono::milliseconds(200)) {
    std::unique_lock<std::mutex> lk(m_);
    if (!cv_.wait_for(lk, limit, [this] { return pending_ == 0; })) {
      ++timeouts_;
      pending_ = 0;
    }
    writing_ = true;
    lk.unlock();
    write();
    lk.lock();
    writing_ = false;
    cv_.notify_all();
  }
  uint64_t timeouts() const {
    std::lock_guard<std::mutex> g(m_);
    return timeouts_;
  }

 private:
  mutable std::mutex m_;
  std::condition_variable cv_;
  int pending_ = 0;
  bool writing_ = false;
  uint64_t timeouts_ = 0;
};

/// The tick writer's listener: counts matched readers (MatchCounter) and tells the gate.
class TickWriterMatch : public MatchCounter {
 public:
  TickWriterMatch(Signal* s, TickFilterGate* gate) : MatchCounter(s), gate_(gate) {}
  void on_publication_matched(eprosima::fastdds::dds::DataWriter* w,
                              const eprosima::fastdds::dds::PublicationMatchedStatus& s) override {
    MatchCounter::on_publication_matched(w, s);
    if (gate_) gate_->matched_changed();
  }

 private:
  TickFilterGate* gate_;
};

/// Registers the tick filter's factory on participant `dp` (once; later calls do nothing). The
/// participant of the tick writer passes its gate; a reader's participant none.
void register_tick_filter(eprosima::fastdds::dds::DomainParticipant* dp, TickFilterGate* gate = nullptr);

/// The filtered view of tick topic `tick` for agent `index` of `side` (registers the filter).
eprosima::fastdds::dds::ContentFilteredTopic* agent_tick_topic(eprosima::fastdds::dds::DomainParticipant* dp,
                                                               eprosima::fastdds::dds::Topic* tick, int side,
                                                               int index);

/// Writer-side filters the plant's tick writer keeps: one per agent's reader, with room to spare
/// for restarted agents whose old reader is not yet unmatched.
inline int tick_filter_capacity(int agents) { return 2 * agents + 16; }

}  // namespace maptr::comm
