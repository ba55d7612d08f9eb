#include "recorder/recorder.hpp"

#include <algorithm>
#include <cstdlib>
#include <set>
#include <stdexcept>

#include "comm/dds/fleet_guid.hpp"
#include "comm/posix/thread_name.hpp"
#include "idl/idl_text.hpp"

namespace maptr::recorder {

namespace dds = eprosima::fastdds::dds;

namespace {
/// Reader history: this many samples per writer of a topic, at least kMinDepth.
constexpr int32_t kSamplesPerWriter = 8;
constexpr int32_t kMinDepth = 256;
/// Writers of the fleet besides its agents (plant, central, two groups, launcher).
constexpr int32_t kOtherWriters = 5;
constexpr const char* kLibrary = "maptr recorder";
/// The file thread is woken by a full batch or this period, whichever comes first: waking it
/// for every sample cost two context switches per sample (docs/bench/HISTORY.md, "The recorder's
/// file thread woken in batches").
constexpr std::size_t kWakeBatch = 512;
constexpr auto kWritePeriod = std::chrono::milliseconds(50);
/// The samples reach the recorder one by one, and each one would wake its receive thread (a
/// context switch per sample, about 7 µs of CPU on this kind of machine: BENCHMARKS.md). When
/// a sample wakes the thread from a wait (none came for kIdleGap), the thread naps kNap first:
/// the samples of the next ticks gather in the recorder's shared-memory port (its queue holds
/// at least 8192, deploy/fleet/config.hpp) and are taken in one turn.
constexpr auto kIdleGap = std::chrono::microseconds(100);
constexpr auto kNap = std::chrono::milliseconds(1);

uint64_t now_ns() {
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::system_clock::now().time_since_epoch())
                                   .count());
}
}  // namespace

Scope parse_scope(const std::string& text) {
  if (text == "all") return Scope::kAll;
  if (text == "plant") return Scope::kPlant;
  if (text == "none") return Scope::kNone;
  throw std::invalid_argument("record = " + text + ": must be all, plant or none");
}

std::vector<comm::FleetTopic> recorded_topics(Scope scope) {
  std::vector<comm::FleetTopic> out;
  for (const auto& t : comm::fleet_topics())
    if (scope == Scope::kAll ||
        (scope == Scope::kPlant && (t.from_plant || t.profile == comm::Profile::kLatched)))
      out.push_back(t);
  return out;
}

int32_t recorder_depth(int agents) {
  return std::max(kMinDepth, kSamplesPerWriter * (agents + kOtherWriters));
}

/// A reader's listener: takes every sample at once and hands it to the recorder.
class Recorder::Tap : public dds::DataReaderListener {
 public:
  Tap(Recorder& r, uint16_t topic) : r_(r), topic_(topic) {}
  void on_data_available(dds::DataReader* reader) override {
    r_.nap_if_woken();
    comm::RawSample s;
    dds::SampleInfo info;
    while (reader->take_next_sample(&s, &info) == ReturnCode_t::RETCODE_OK)
      if (info.valid_data)
        r_.push(topic_, info.publication_handle, info.source_timestamp, std::move(s.bytes));
    r_.taken();
  }
  /// For tests only: the first start's writer of this process is never counted as matched.
  void deaf_to(uint32_t fleet_id, int base_participant_id) {
    deaf_fleet_ = fleet_id;
    deaf_id_ = base_participant_id;
  }
  void on_subscription_matched(dds::DataReader*, const dds::SubscriptionMatchedStatus& s) override {
    std::lock_guard<std::mutex> g(m_);
    if (deaf_id_ >= 0 && comm::fleet_participant(deaf_fleet_, s.last_publication_handle) == deaf_id_) return;
    if (s.current_count_change > 0)
      writers_.insert(s.last_publication_handle);
    else if (s.current_count_change < 0)
      writers_.erase(s.last_publication_handle);
    matched_.store(static_cast<int>(writers_.size()));
  }
  int matched() const { return matched_.load(); }
  std::vector<eprosima::fastrtps::rtps::InstanceHandle_t> writers() const {
    std::lock_guard<std::mutex> g(m_);
    return {writers_.begin(), writers_.end()};
  }

 private:
  Recorder& r_;
  uint16_t topic_;
  std::atomic<int> matched_{0};
  mutable std::mutex m_;
  std::set<eprosima::fastrtps::rtps::InstanceHandle_t> writers_;
  uint32_t deaf_fleet_ = 0;
  int deaf_id_ = -1;
};

namespace {
std::string& hidden_agent() {
  static std::string name;
  return name;
}
}  // namespace

void hide_first_answer_writer_of(const std::string& name) { hidden_agent() = name; }

Recorder::Recorder(const comm::DdsOptions& o, const std::string& path, Scope scope, int agents,
                   const std::string& compression)
    : topics_(recorded_topics(scope)), fleet_id_(o.fleet_id), agents_(agents) {
  file_ = std::make_unique<records::mcap::Writer>(path, "", kLibrary,
                                                  records::mcap::Writer::kDefaultChunkBytes, compression);
  std::map<std::string, uint16_t> schema_of;
  for (const auto& t : topics_) {
    if (!schema_of.count(t.type_name))
      schema_of[t.type_name] = file_->add_schema(t.type_name, "omgidl", msg::idl_text());
    schema_.push_back(schema_of[t.type_name]);
  }
  counts_.assign(topics_.size(), 0);
  writer_ = std::thread([this] { write_loop(); });
  participant_ = std::make_unique<comm::Participant>("recorder", o);
  for (std::size_t i = 0; i < topics_.size(); ++i) {
    const auto& t = topics_[i];
    taps_.push_back(std::make_unique<Tap>(*this, static_cast<uint16_t>(i)));
    if (!hidden_agent().empty() && t.topic == std::string(comm::topic::kAgentReply) && o.fleet_id != 0)
      taps_.back()->deaf_to(o.fleet_id, comm::base_participant_id(hidden_agent(), agents));
    auto* topic = participant_->topic(t.topic, new comm::RawType(t.type_name, t.max_size));
    participant_->reader(topic, t.profile, taps_.back().get(), recorder_depth(agents));
  }
}

Recorder::~Recorder() {
  try {
    stop();
  } catch (...) {
  }
}

void Recorder::nap_if_woken() {
  const auto since =
      std::chrono::steady_clock::now().time_since_epoch() - std::chrono::nanoseconds(last_take_ns_.load());
  if (since > kIdleGap) std::this_thread::sleep_for(kNap);
}

void Recorder::taken() {
  last_take_ns_.store(std::chrono::duration_cast<std::chrono::nanoseconds>(
                          std::chrono::steady_clock::now().time_since_epoch())
                          .count());
}

void Recorder::push(uint16_t topic, const eprosima::fastrtps::rtps::InstanceHandle_t& writer,
                    const eprosima::fastrtps::rtps::Time_t& source, std::string&& bytes) {
  {
    std::lock_guard<std::mutex> g(m_);
    if (stopping_) return;  // a participant Fast DDS could not delete (comm::participant_left_open())
    const uint64_t publish_ns = static_cast<uint64_t>(source.seconds()) * 1000000000ull + source.nanosec();
    // The log time is taken under the lock: log times rise in file order.
    queue_.push_back({topic, writer, now_ns(), publish_ns, std::move(bytes)});
    ++counts_[topic];
    if (queue_.size() < kWakeBatch) return;  // the file thread comes by within kWritePeriod
  }
  cv_.notify_one();
}

void Recorder::write_loop() {
  comm::name_this_thread(comm::kRecorderThread);
  std::unique_lock<std::mutex> lk(m_);
  for (;;) {
    cv_.wait_for(lk, kWritePeriod, [this] { return stopping_ || queue_.size() >= kWakeBatch; });
    if (queue_.empty() && !stopping_) continue;
    std::deque<Pending> batch;
    batch.swap(queue_);
    const bool last = stopping_;
    lk.unlock();
    for (auto& p : batch) {
      records::mcap::Message m;
      m.channel_id = channel_of(p);
      m.sequence = ++sequence_[m.channel_id];
      m.log_time_ns = p.log_ns;
      m.publish_time_ns = p.publish_ns;
      m.data = std::move(p.bytes);
      file_->write(m);
    }
    lk.lock();
    if (last && queue_.empty()) return;
  }
}

uint16_t Recorder::channel_of(const Pending& p) {
  auto name = writers_.find(p.writer);
  if (name == writers_.end())
    name = writers_.emplace(p.writer, comm::writer_process(fleet_id_, agents_, p.writer)).first;
  const Verdict v = judge_sample(topics_[p.topic].topic, p.bytes, name->second, agents_);
  ++verdicts_[static_cast<std::size_t>(v)];
  const ChannelKey key{p.topic, p.writer, v};
  const auto it = channels_.find(key);
  if (it != channels_.end()) return it->second;
  const uint16_t id = file_->add_channel(schema_[p.topic], topics_[p.topic].topic, "cdr",
                                         {{kWriterKey, comm::prefix_text(p.writer)},
                                          {kProcessKey, name->second},
                                          {kVerdictKey, verdict_name(v)}});
  channels_.emplace(key, id);
  sequence_.resize(static_cast<std::size_t>(id) + 1, 0);
  return id;
}

bool Recorder::wait_matched(const std::map<std::string, int>& writers,
                            std::chrono::steady_clock::time_point deadline) {
  for (;;) {
    missing_.clear();
    for (std::size_t i = 0; i < topics_.size(); ++i) {
      const auto it = writers.find(topics_[i].topic);
      if (it != writers.end() && taps_[i]->matched() < it->second)
        missing_ += (missing_.empty() ? "" : ", ") + topics_[i].topic + " " +
                    std::to_string(taps_[i]->matched()) + "/" + std::to_string(it->second);
    }
    if (missing_.empty()) return true;
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

std::vector<eprosima::fastrtps::rtps::InstanceHandle_t> Recorder::matched_writers(
    const std::string& topic) const {
  for (std::size_t i = 0; i < topics_.size(); ++i)
    if (topics_[i].topic == topic) return taps_[i]->writers();
  return {};
}

void Recorder::stop() {
  if (!participant_ && !writer_.joinable()) return;
  participant_.reset();  // no callback runs after this, unless Fast DDS left it open (then push() drops)
  {
    std::lock_guard<std::mutex> g(m_);
    stopping_ = true;
  }
  cv_.notify_one();
  if (writer_.joinable()) writer_.join();
  file_->close();
}

std::map<std::string, uint64_t> Recorder::rejected() const {
  std::map<std::string, uint64_t> out;
  for (std::size_t v = 1; v < verdicts_.size(); ++v)
    if (const uint64_t n = verdicts_[v].load()) out[verdict_name(static_cast<Verdict>(v))] = n;
  return out;
}

std::map<std::string, uint64_t> Recorder::counts() const {
  std::lock_guard<std::mutex> g(m_);
  std::map<std::string, uint64_t> out;
  for (std::size_t i = 0; i < topics_.size(); ++i) out[topics_[i].topic] = counts_[i];
  return out;
}

}  // namespace maptr::recorder
