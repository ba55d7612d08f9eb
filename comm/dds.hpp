#pragma once
// Small Fast DDS glue shared by every MAPTR process: participant set-up (discovery, transports,
// leases), the two QoS profiles the protocol uses, typed writers, and readers whose listener
// only hands samples to the owning loop (DDS callbacks never run the node's logic).
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

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace maptr::comm {

/// How a participant finds the others.
struct DdsOptions {
  int domain = 0;                       ///< DDS domain id (tests use a private one)
  /// "HOST:PORT[,HOST:PORT...]": be a client of every one of these servers (server i has the
  /// GUID prefix of index i); empty: simple discovery
  std::string discovery_server;
  int server_index = 0;                 ///< is_server: which entry of discovery_server this is
  double lease_s = 2.0;                 ///< participant and liveliness lease, s
  bool is_server = false;               ///< this participant is the discovery server
  uint32_t shm_segment_bytes = 0;       ///< 0: Fast DDS default
  int participant_id = -1;              ///< explicit id (sets its ports); -1: Fast DDS picks one
  bool shm = true;                      ///< shared memory for data (else UDP only)
  std::string interface_address = "127.0.0.1";  ///< the one IPv4 interface UDP uses
  uint32_t fleet_id = 0;                ///< the run's fleet id (comm/fleet_ids.hpp); 0: none
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
}  // namespace topic

/// The QoS profiles of the protocol, defined in comm/maptr_qos.xml (installed as
/// bin/maptr_qos.xml; FASTRTPS_DEFAULT_PROFILES_FILE replaces it).
enum class Profile {
  kStream,   ///< lock-step data: reliable, keep-last, volatile, fast heartbeats
  kLatched,  ///< events and readiness: reliable, transient-local, keep-all
};

/// The XML file the QoS profiles come from (loaded once per process).
std::string qos_profiles_file();

/// Wakes a node's loop when any of its readers received data.
class Signal {
 public:
  void notify();
  /// Waits until notified after `seen` (a value returned earlier) or until the deadline.
  uint64_t wait_until(uint64_t seen, std::chrono::steady_clock::time_point deadline);
  uint64_t count() const { return count_.load(); }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  std::atomic<uint64_t> count_{0};
};

/// Liveliness change seen by a reader (writer handle, alive or lost); an unmatched writer
/// counts as lost.
struct LivelinessEvent {
  eprosima::fastrtps::rtps::InstanceHandle_t writer;
  bool alive = false;
};

/// Reader listener that takes every valid sample into a queue and signals the loop.
template <class T>
class Inbox : public eprosima::fastdds::dds::DataReaderListener {
 public:
  explicit Inbox(Signal& s) : signal_(s) {}

  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override {
    T sample;
    eprosima::fastdds::dds::SampleInfo info;
    bool any = false;
    while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      std::lock_guard<std::mutex> g(m_);
      q_.emplace_back(sample, info.publication_handle);
      any = true;
    }
    if (any) signal_.notify();
  }
  void on_subscription_matched(eprosima::fastdds::dds::DataReader*,
                               const eprosima::fastdds::dds::SubscriptionMatchedStatus& s) override {
    matched_.store(s.current_count);
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

 private:
  Signal& signal_;
  std::mutex m_;
  std::deque<std::pair<T, eprosima::fastrtps::rtps::InstanceHandle_t>> q_;
  std::deque<LivelinessEvent> live_;
  std::atomic<int> matched_{0};
};

/// Writer listener that counts matched readers.
class MatchCounter : public eprosima::fastdds::dds::DataWriterListener {
 public:
  explicit MatchCounter(Signal* s = nullptr) : signal_(s) {}
  void on_publication_matched(eprosima::fastdds::dds::DataWriter*,
                              const eprosima::fastdds::dds::PublicationMatchedStatus& s) override {
    matched_.store(s.current_count);
    if (signal_) signal_->notify();
  }
  int matched() const { return matched_.load(); }

 private:
  Signal* signal_;
  std::atomic<int> matched_{0};
};

/// A participant with one publisher and one subscriber; owns every entity it creates
/// (delete_contained_entities() on destruction). With a fleet id and an explicit participant id,
/// its GUID prefix is the fleet's (comm/fleet_ids.hpp).
class Participant {
 public:
  Participant(const std::string& name, const DdsOptions& o);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  /// Registers type T (a fastddsgen PubSubType) once and returns the topic (the same one on
  /// every call with the same name).
  template <class PubSubType>
  eprosima::fastdds::dds::Topic* topic(const std::string& name) {
    eprosima::fastdds::dds::TypeSupport ts(new PubSubType());
    return make_topic(name, ts);
  }

  eprosima::fastdds::dds::DataWriter* writer(eprosima::fastdds::dds::Topic* t, Profile p,
                                             eprosima::fastdds::dds::DataWriterListener* l = nullptr);
  eprosima::fastdds::dds::DataReader* reader(eprosima::fastdds::dds::Topic* t, Profile p,
                                             eprosima::fastdds::dds::DataReaderListener* l);
  eprosima::fastdds::dds::DomainParticipant* raw() { return dp_; }
  const DdsOptions& options() const { return o_; }

 private:
  eprosima::fastdds::dds::Topic* make_topic(const std::string& name, eprosima::fastdds::dds::TypeSupport& ts);

  DdsOptions o_;
  eprosima::fastdds::dds::DomainParticipant* dp_ = nullptr;
  eprosima::fastdds::dds::Publisher* pub_ = nullptr;
  eprosima::fastdds::dds::Subscriber* sub_ = nullptr;
};

/// The entries of a comma-separated list of discovery servers.
std::vector<std::string> split_servers(const std::string& list);

/// Reads MAPTR_DOMAIN, MAPTR_DISCOVERY_SERVER, MAPTR_DISCOVERY_INDEX, MAPTR_LEASE_S,
/// MAPTR_TRANSPORT, MAPTR_INTERFACE, MAPTR_PARTICIPANT_ID, MAPTR_SHM_SEGMENT_BYTES and
/// MAPTR_FLEET_ID into the options (the
/// launcher sets them for its children); explicit command-line values override them.
DdsOptions options_from_env();

/// Removes Fast DDS shared-memory files in /dev/shm that no live process holds any more:
/// `fastdds shm clean` for segments, then the unused port files it leaves
/// (remove_unused_shm_ports): those of `own_ports` at any age (a fleet's own, once every
/// process of it has ended), the others once 10 s old. Returns how many port groups went.
int clean_stale_shm(const std::set<int>& own_ports = {});

}  // namespace maptr::comm
