#pragma once
// Small Fast DDS glue shared by every MAPTR process: participant set-up (discovery, transports,
// leases), the two QoS profiles the protocol uses, typed writers, and readers whose listener
// only hands samples to the owning loop (DDS callbacks never run the node's logic).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "comm/dds/checked_type.hpp"

namespace maptr::comm {

/// How a participant finds the others.
struct DdsOptions {
  int domain = 0;  ///< DDS domain id (tests use a private one)
  /// "HOST:PORT[,HOST:PORT...]": be a client of these servers (all, or own_server; server i has the
  /// GUID prefix of index i); empty: simple discovery
  std::string discovery_server;
  int server_index = 0;  ///< is_server: which entry of discovery_server this is
  /// A client: register only with this entry of discovery_server (its own host's server on a
  /// fleet of several hosts); -1: with every one.
  int own_server = -1;
  double lease_s = 2.0;            ///< participant and liveliness lease, s
  bool is_server = false;          ///< this participant is the discovery server
  uint32_t shm_segment_bytes = 0;  ///< 0: Fast DDS default
  /// MAPTR_DDS_LOG: Fast DDS's own log on the process's stderr from this level on ("error",
  /// "warning" or "info"; empty: Fast DDS's default, errors only).
  std::string dds_log;
  int participant_id = -1;      ///< explicit id (sets its ports); -1: Fast DDS picks one
  bool shm = true;              ///< shared memory for data (else UDP only)
  bool shm_data_only = true;    ///< with shm: user data on shared memory only, UDP for discovery
  uint32_t shm_port_queue = 0;  ///< messages the shared-memory listening port holds; 0: default
  /// Bytes of the UDP sockets' receive buffers (0: the system's default; the kernel caps it at
  /// net.core.rmem_max).
  uint32_t udp_receive_buffer_bytes = 0;
  std::string interface_address = "127.0.0.1";  ///< the one IPv4 interface UDP uses
  uint32_t fleet_id = 0;                        ///< the run's fleet id (comm/dds/fleet_ids.hpp); 0: none
  /// Folder of a secure domain (comm/dds/security.hpp): the participant authenticates as the
  /// identity of its name, encrypts and enforces its permissions; empty: a plain domain.
  std::string security_dir;
};

/// Topic names (one place).
namespace topic {
inline constexpr const char* kTick = "maptr/tick";
inline constexpr const char* kAgentReply = "maptr/agent_reply";
inline constexpr const char* kCentral = "maptr/central";
inline constexpr const char* kGroup = "maptr/group";
inline constexpr const char* kReady = "maptr/ready";
inline constexpr const char* kMembership = "maptr/membership";
inline constexpr const char* kControl = "maptr/control";
inline constexpr const char* kGate = "maptr/gate";
/// The plant's NodeReady again, to every member before tick 0: its write opens each member's
/// shared-memory port, which tick 0 would otherwise open one by one (BENCHMARKS.md, tick 0).
inline constexpr const char* kHello = "maptr/hello";
}  // namespace topic

/// The QoS profiles of the protocol, defined in comm/dds/maptr_qos.xml (installed as
/// bin/maptr_qos.xml; FASTRTPS_DEFAULT_PROFILES_FILE replaces it).
enum class Profile {
  kStream,          ///< lock-step data: best effort, keep-last, volatile (the lock-step repairs a loss)
  kLatched,         ///< events and readiness: reliable, transient-local, keep-all
  kReliableStream,  ///< lock-step data where nothing repairs a loss (a replay): reliable, keep-last
};

/// The XML file the QoS profiles come from (loaded once per process).
std::string qos_profiles_file();

/// Wakes a node's loop when any of its readers received data. Lock-step samples are counted
/// (arrived()): the loop says how many it waits for (wake_at()) and is woken once, when the
/// last of them arrives, instead of once per sample.
class Signal {
 public:
  void notify();
  /// n counted samples arrived: wakes the loop when the total reaches the wake-up mark.
  void arrived(uint64_t n);
  /// Wake the loop when the total of counted samples reaches `total` (0: at every sample).
  void wake_at(uint64_t total) { wake_at_.store(total); }
  /// Counted samples so far.
  uint64_t arrivals() const { return arrived_.load(); }
  /// Waits until notified after `seen` (a value returned earlier) or until the deadline.
  uint64_t wait_until(uint64_t seen, std::chrono::steady_clock::time_point deadline);
  uint64_t count() const { return count_.load(); }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  std::atomic<uint64_t> count_{0};
  std::atomic<uint64_t> arrived_{0};
  std::atomic<uint64_t> wake_at_{0};
};

/// Liveliness change seen by a reader (writer handle, alive or lost); an unmatched writer
/// counts as lost.
struct LivelinessEvent {
  eprosima::fastrtps::rtps::InstanceHandle_t writer;
  bool alive = false;
};

/// The remote endpoints an endpoint is matched with now, kept from its match events (Fast DDS
/// 2.9 does not implement get_matched_publications/subscriptions). Touched at a match only.
class MatchedEndpoints {
 public:
  void changed(const eprosima::fastrtps::rtps::InstanceHandle_t& h, int32_t count_change) {
    std::lock_guard<std::mutex> g(m_);
    if (count_change > 0) now_.insert(h);
    if (count_change < 0) now_.erase(h);
  }
  std::vector<eprosima::fastrtps::rtps::InstanceHandle_t> now() const {
    std::lock_guard<std::mutex> g(m_);
    return {now_.begin(), now_.end()};
  }

 private:
  mutable std::mutex m_;
  std::set<eprosima::fastrtps::rtps::InstanceHandle_t> now_;
};

/// How an inbox wakes its loop when samples arrive.
enum class Wake {
  kEach,     ///< at every batch of samples
  kCounted,  ///< counted lock-step samples: once the loop's wake-up mark is reached (Signal::arrived)
  kNever,    ///< never: the loop polls it (samples it only looks at now and then)
};

/// Reader listener that takes every valid sample into a queue and wakes the loop as `wake` says;
/// a payload that does not deserialize (CheckedType) is dropped and counted.
template <class T>
class Inbox : public eprosima::fastdds::dds::DataReaderListener {
 public:
  explicit Inbox(Signal& s, Wake wake = Wake::kEach) : signal_(s), wake_(wake) {}

  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override {
    T sample;
    eprosima::fastdds::dds::SampleInfo info;
    uint64_t n = 0;
    while (take_counting(reader, &sample, info)) {
      if (!info.valid_data) continue;
      std::lock_guard<std::mutex> g(m_);
      q_.emplace_back(sample, info.publication_handle);
      ++n;
    }
    if (n == 0 || wake_ == Wake::kNever) return;
    if (wake_ == Wake::kCounted)
      signal_.arrived(n);
    else
      signal_.notify();
  }
  void on_subscription_matched(eprosima::fastdds::dds::DataReader*,
                               const eprosima::fastdds::dds::SubscriptionMatchedStatus& s) override {
    matched_.store(s.current_count);
    writers_.changed(s.last_publication_handle, s.current_count_change);
    if (s.current_count_change < 0) {
      // A writer went away: lost liveliness that removed its participant shows up here.
      std::lock_guard<std::mutex> g(m_);
      live_.push_back({s.last_publication_handle, false});
    }
    signal_.notify();
  }
  void on_liveliness_changed(eprosima::fastdds::dds::DataReader*,
                             const eprosima::fastdds::dds::LivelinessChangedStatus& s) override {
    std::lock_guard<std::mutex> g(m_);
    if (s.not_alive_count_change > 0) live_.push_back({s.last_publication_handle, false});
    if (s.alive_count_change > 0) live_.push_back({s.last_publication_handle, true});
    signal_.notify();
  }

  /// Moves out what arrived since the last call.
  std::vector<std::pair<T, eprosima::fastrtps::rtps::InstanceHandle_t>> drain() {
    std::lock_guard<std::mutex> g(m_);
    std::vector<std::pair<T, eprosima::fastrtps::rtps::InstanceHandle_t>> out(
        std::make_move_iterator(q_.begin()), std::make_move_iterator(q_.end()));
    q_.clear();
    return out;
  }
  std::vector<LivelinessEvent> drain_liveliness() {
    std::lock_guard<std::mutex> g(m_);
    std::vector<LivelinessEvent> out(live_.begin(), live_.end());
    live_.clear();
    return out;
  }
  int matched() const { return matched_.load(); }
  /// The writers matched now (their handles hold their GUIDs).
  std::vector<eprosima::fastrtps::rtps::InstanceHandle_t> matched_writers() const { return writers_.now(); }
  /// Samples dropped so far because their payload did not deserialize.
  uint64_t undecodable() const { return undecodable_.load(); }

  /// Takes the next sample that deserializes; false when none is left. A sample whose payload
  /// CheckedType refused is counted as undecodable and skipped: Fast DDS 2.9.1 answers NO_DATA
  /// for it (older versions OK with the sample unset), and the samples behind it are still
  /// there (tests/comm/test_undecodable.cpp). At most kMaxRefused refusals per call, should a
  /// refused sample ever stay at the head of the history.
  bool take_counting(eprosima::fastdds::dds::DataReader* reader, T* sample,
                     eprosima::fastdds::dds::SampleInfo& info) {
    constexpr int kMaxRefused = 4096;
    for (int refused = 0; refused < kMaxRefused; ++refused) {
      t_deserialize_failed = false;
      const bool ok = reader->take_next_sample(sample, &info) == ReturnCode_t::RETCODE_OK;
      if (!last_deserialize_failed()) return ok;
      t_deserialize_failed = false;
      undecodable_.fetch_add(1);
    }
    return false;
  }

 protected:
  void count_undecodable() { undecodable_.fetch_add(1); }

 private:
  Signal& signal_;
  const Wake wake_;
  std::mutex m_;
  std::deque<std::pair<T, eprosima::fastrtps::rtps::InstanceHandle_t>> q_;
  std::deque<LivelinessEvent> live_;
  std::atomic<int> matched_{0};
  std::atomic<uint64_t> undecodable_{0};
  MatchedEndpoints writers_;
};

/// Reader listener that hands each valid sample straight to a handler on the DDS receive thread,
/// so a lock-step answer leaves without waking another thread; until a handler is set (and after
/// it is cleared) samples are queued as in Inbox. Matching and liveliness go to the loop as in
/// Inbox. Calls of the handler are serialised.
template <class T>
class Direct : public Inbox<T> {
 public:
  using Handler = std::function<void(const T&, const eprosima::fastrtps::rtps::InstanceHandle_t&)>;
  using Inbox<T>::Inbox;

  /// Samples go to h from now on, those queued before first; an empty h queues them again.
  void set_handler(Handler h) {
    std::lock_guard<std::mutex> g(handler_m_);
    if (h)
      for (auto& [sample, writer] : Inbox<T>::drain()) h(sample, writer);
    handler_ = std::move(h);
  }

  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override {
    std::lock_guard<std::mutex> g(handler_m_);
    if (!handler_) {
      Inbox<T>::on_data_available(reader);
      return;
    }
    eprosima::fastdds::dds::SampleInfo info;
    // One sample object for every take: deserializing into it keeps the capacity of its
    // sequences, so a tick costs no allocation (every field is written by each deserialize).
    while (Inbox<T>::take_counting(reader, &sample_, info))
      if (info.valid_data) handler_(sample_, info.publication_handle);
  }

 private:
  std::mutex handler_m_;
  Handler handler_;
  T sample_;  ///< guarded by handler_m_
};

/// Writer listener that counts matched readers. After only_fleet(id) (before the writer is
/// created) it counts only the readers of that fleet (their GUID prefix, comm/dds/fleet_guid.hpp), so
/// that a watcher on the domain, such as `maptr top`, is never taken for a member.
class MatchCounter : public eprosima::fastdds::dds::DataWriterListener {
 public:
  explicit MatchCounter(Signal* s = nullptr) : signal_(s) {}
  void only_fleet(uint32_t fleet_id) { fleet_id_ = fleet_id; }
  void on_publication_matched(eprosima::fastdds::dds::DataWriter*,
                              const eprosima::fastdds::dds::PublicationMatchedStatus& s) override;
  int matched() const { return matched_.load(); }
  /// The readers matched now, of the fleet or not (their handles hold their GUIDs).
  std::vector<eprosima::fastrtps::rtps::InstanceHandle_t> matched_readers() const { return readers_.now(); }

 private:
  Signal* signal_;
  uint32_t fleet_id_ = 0;
  std::atomic<int> matched_{0};
  MatchedEndpoints readers_;
};

/// A participant with one publisher and one subscriber; owns every entity it creates
/// (delete_contained_entities() on destruction). With a fleet id and an explicit participant id,
/// its GUID prefix is the fleet's (comm/dds/fleet_ids.hpp). With a security folder, `name` is also
/// its identity (NAME.cert.pem, NAME.permissions.p7s there). The listeners given to reader()
/// and writer() must outlive it (declare them before it): deleting its entities still calls them.
class Participant {
 public:
  Participant(const std::string& name, const DdsOptions& o);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  /// Registers type T (a fastddsgen PubSubType, whose deserialize never throws here:
  /// CheckedType) once and returns the topic (the same one on every call with the same name).
  template <class PubSubType>
  eprosima::fastdds::dds::Topic* topic(const std::string& name) {
    eprosima::fastdds::dds::TypeSupport ts(new CheckedType<PubSubType>());
    return make_topic(name, ts);
  }

  /// The topic `name` of a type given at run time (comm/dds/raw_type.hpp); takes `type`.
  eprosima::fastdds::dds::Topic* topic(const std::string& name, eprosima::fastdds::dds::TopicDataType* type) {
    eprosima::fastdds::dds::TypeSupport ts(type);
    return make_topic(name, ts);
  }

  /// A latched writer of a participant whose user data is on shared memory only takes its
  /// acknowledgements on the participant's UDP metatraffic port (metatraffic_udp_locator()): a
  /// reader that has UDP only (maptr top) can then acknowledge. A reliable Fast DDS writer sends
  /// a late-joining reader neither the history nor new samples until that reader has
  /// acknowledged once, and such a reader's acknowledgements to a shared-memory locator are lost.
  ///
  /// With `reader_filters` > 0, the writer evaluates the content filters of up to that many
  /// readers before it sends (writer-side filtering, comm/lockstep/tick_filter.hpp); 0: none,
  /// each reader filters itself.
  eprosima::fastdds::dds::DataWriter* writer(eprosima::fastdds::dds::Topic* t, Profile p,
                                             eprosima::fastdds::dds::DataWriterListener* l = nullptr,
                                             int32_t reader_filters = 0);
  /// A reader of a topic or of a filtered view of one (a ContentFilteredTopic). With `depth` > 0
  /// its history keeps the last `depth` samples (a recorder's, deeper than what the fleet's
  /// writers send in one burst); 0: the profile's history.
  eprosima::fastdds::dds::DataReader* reader(eprosima::fastdds::dds::TopicDescription* t, Profile p,
                                             eprosima::fastdds::dds::DataReaderListener* l = nullptr,
                                             int32_t depth = 0);
  eprosima::fastdds::dds::DomainParticipant* raw() { return dp_; }
  const DdsOptions& options() const { return o_; }

 private:
  eprosima::fastdds::dds::Topic* make_topic(const std::string& name, eprosima::fastdds::dds::TypeSupport& ts);
  /// Sets the UDP acknowledgement locator of a latched writer (see writer()) when this
  /// participant's user data is on shared memory only and its metatraffic port is its own.
  void add_latched_ack_locator(eprosima::fastdds::dds::DataWriterQos& q) const;

  DdsOptions o_;
  std::optional<eprosima::fastrtps::rtps::Locator_t> latched_ack_;  ///< set at construction
  eprosima::fastdds::dds::DomainParticipant* dp_ = nullptr;
  eprosima::fastdds::dds::Publisher* pub_ = nullptr;
  eprosima::fastdds::dds::Subscriber* sub_ = nullptr;
};

/// Bounds the deletion of every Participant of this process from now on: a deletion that has
/// not returned after `seconds` is left to run on (its thread detached) and the destructor
/// returns. Fast DDS 2.9 with security can deadlock two of its own threads when a remote
/// participant leaves while it checks another one's lease (eProsima/Fast-DDS#6502); the
/// deletion then waits forever. 0 (the default): unbounded.
void bound_participant_deletion(double seconds);

/// True once a deletion was left running (see bound_participant_deletion()). Such a process
/// must end with _exit: the participant factory's static destructor would wait on it again.
bool participant_left_open();

/// The UDP locator of participant `participant_id`'s metatraffic unicast port on `o`'s domain and
/// interface (RTPS port d1); none for an id Fast DDS picks itself (participant_id < 0).
std::optional<eprosima::fastrtps::rtps::Locator_t> metatraffic_udp_locator(const DdsOptions& o);

/// The unicast shared-memory locator Fast DDS uses for this host (port 0: the participant's own
/// well-known port is filled in at creation).
eprosima::fastrtps::rtps::Locator_t shm_unicast_locator();

/// The entries of a comma-separated list of discovery servers.
std::vector<std::string> split_servers(const std::string& list);

/// Reads MAPTR_DOMAIN, MAPTR_DISCOVERY_SERVER (one or a comma-separated list), MAPTR_LEASE_S,
/// MAPTR_INTERFACE, MAPTR_TRANSPORT ("shm": data on shared memory only; "shm+udp": data on both; "udp":
/// loopback UDP only), MAPTR_SHM_PORT_QUEUE, MAPTR_PARTICIPANT_ID, MAPTR_SHM_SEGMENT_BYTES, MAPTR_FLEET_ID
/// and MAPTR_SECURITY_DIR into the options (the launcher sets them for its children); explicit command-line
/// values override them.
DdsOptions options_from_env();

/// Removes Fast DDS shared-memory files in /dev/shm that no live process holds any more:
/// `fastdds shm clean` for segments, then the unused port files it leaves
/// (remove_unused_shm_ports): those of `own_ports` at any age (a fleet's own, once every
/// process of it has ended), the others once 10 s old. Returns how many port groups went.
int clean_stale_shm(const std::set<int>& own_ports = {});

}  // namespace maptr::comm
