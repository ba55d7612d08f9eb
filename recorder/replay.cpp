#include "recorder/replay.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "comm/dds/checked_type.hpp"
#include "comm/dds/raw_type.hpp"
#include "idl/maptrPubSubTypes.h"
#include "recorder/recorder.hpp"

namespace maptr::recorder {

namespace dds = eprosima::fastdds::dds;
using Clock = std::chrono::steady_clock;

bool taken(const records::mcap::Channel& ch) {
  const auto v = ch.metadata.find(kVerdictKey);
  return v == ch.metadata.end() || v->second == verdict_name(Verdict::kTaken);
}

namespace {
/// Preallocated payload of a topic the fleet does not know, bytes (longer samples reallocate).
constexpr uint32_t kUnknownTypeSize = 4096;
constexpr auto kPoll = std::chrono::milliseconds(20);
constexpr double kProgressPeriodS = 1.0;

/// One writer per topic of the file, with its schema's type name, for every channel replayed.
std::map<uint16_t, dds::DataWriter*> make_writers(comm::Participant& p, const records::mcap::File& f,
                                                  bool with_rejected) {
  std::map<std::string, dds::DataWriter*> by_topic;
  std::map<uint16_t, dds::DataWriter*> out;
  for (const auto& [id, ch] : f.channels) {
    const auto s = f.schemas.find(ch.schema_id);
    if (s == f.schemas.end() || ch.message_encoding != "cdr" || (!with_rejected && !taken(ch))) continue;
    auto& w = by_topic[ch.topic];
    if (!w) {
      const comm::FleetTopic* known = comm::find_fleet_topic(ch.topic);
      const uint32_t size = known ? known->max_size : kUnknownTypeSize;
      auto* topic = p.topic(ch.topic, new comm::RawType(s->second.name, size));
      // Nothing repairs a lost sample of a replay: the lock-step topics go out reliably.
      const comm::Profile profile = known && known->profile == comm::Profile::kLatched
                                        ? comm::Profile::kLatched
                                        : comm::Profile::kReliableStream;
      w = p.writer(topic, profile);
    }
    out[id] = w;
  }
  return out;
}

/// The simulated time of a PlantTick message (nullopt for other messages or a tick that does not decode).
std::optional<double> tick_time(const records::mcap::File& f, const records::mcap::Message& m) {
  const auto ch = f.channels.find(m.channel_id);
  if (ch == f.channels.end() || ch->second.topic != comm::topic::kTick) return std::nullopt;
  msg::PlantTick tick;
  if (!comm::decode<msg::PlantTickPubSubType>(m.data, tick)) return std::nullopt;
  return tick.t();
}

void wait_for_reader(dds::DataWriter* w, double seconds, const std::atomic<bool>& stop) {
  const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
  dds::PublicationMatchedStatus st;
  while (!stop.load() && Clock::now() < deadline) {
    w->get_publication_matched_status(st);
    if (st.current_count > 0) return;
    std::this_thread::sleep_for(kPoll);
  }
}
}  // namespace

ReplayResult replay(const records::mcap::File& file, const comm::DdsOptions& o, const ReplayOptions& r,
                    const std::atomic<bool>& stop, const std::function<void(uint64_t)>& progress) {
  if (!(r.rate > 0)) throw std::invalid_argument("--rate must be above 0");
  ReplayResult res;
  if (file.messages.empty()) return res;
  comm::Participant p("replay", o);
  const auto writers = make_writers(p, file, r.with_rejected);
  for (const auto& [id, w] : writers)
    if (file.channels.at(id).topic == comm::topic::kTick) wait_for_reader(w, r.wait_reader_s, stop);
  std::vector<const records::mcap::Message*> order;
  for (const auto& m : file.messages) order.push_back(&m);
  std::stable_sort(order.begin(), order.end(),
                   [](auto* a, auto* b) { return a->log_time_ns < b->log_time_ns; });
  const uint64_t first = order.front()->log_time_ns;
  const auto t0 = Clock::now();
  auto last_progress = t0;
  comm::RawSample s;
  std::optional<double> first_tick_t;
  double last_tick_t = 0.0;
  for (const auto* m : order) {
    if (stop.load()) break;
    // A tick waits for its simulated time; everything else follows the tick before it.
    if (const auto t = tick_time(file, *m)) {
      if (!first_tick_t) first_tick_t = *t;
      last_tick_t = *t;
      const double at_s = (*t - *first_tick_t) / r.rate;
      std::this_thread::sleep_until(
          t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(at_s)));
    }
    const auto w = writers.find(m->channel_id);
    if (w == writers.end()) {
      ++res.left_out;
      continue;
    }
    s.bytes = m->data;
    if (w->second->write(&s)) ++res.messages;
    if (progress && Clock::now() - last_progress > std::chrono::duration<double>(kProgressPeriodS)) {
      last_progress = Clock::now();
      progress(res.messages);
    }
  }
  res.wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
  res.recorded_s = static_cast<double>(order.back()->log_time_ns - first) * 1e-9;
  res.simulated_s = first_tick_t ? last_tick_t - *first_tick_t : 0.0;
  for (const auto& [id, w] : writers) w->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(r.linger_s));
  return res;
}

}  // namespace maptr::recorder
