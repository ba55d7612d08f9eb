#include "comm/dds/dds.hpp"

#include <fastrtps/utils/IPLocator.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <filesystem>
#include <future>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "comm/dds/fleet_guid.hpp"
#include "comm/dds/participant_qos.hpp"
#include "comm/dds/security.hpp"
#include "comm/posix/environment.hpp"
#include "comm/posix/shm_files.hpp"
#include "comm/posix/udp_ports.hpp"

namespace maptr::comm {

namespace dds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;

void Signal::notify() {
  {
    std::lock_guard<std::mutex> g(m_);
    count_.fetch_add(1);
  }
  cv_.notify_all();
}

void Signal::arrived(uint64_t n) {
  const uint64_t total = arrived_.fetch_add(n) + n;
  if (total >= wake_at_.load()) notify();
}

uint64_t Signal::wait_until(uint64_t seen, std::chrono::steady_clock::time_point deadline) {
  std::unique_lock<std::mutex> lk(m_);
  cv_.wait_until(lk, deadline, [&] { return count_.load() != seen; });
  return count_.load();
}

void MatchCounter::on_publication_matched(dds::DataWriter*, const dds::PublicationMatchedStatus& s) {
  readers_.changed(s.last_subscription_handle, s.current_count_change);
  if (fleet_id_ == 0)
    matched_.store(s.current_count);
  else if (fleet_participant(fleet_id_, s.last_subscription_handle) ||
           secure_identity(eprosima::fastrtps::rtps::iHandle2GUID(s.last_subscription_handle).guidPrefix))
    matched_.fetch_add(s.current_count_change);  // on a secure domain: a certified member
  if (signal_) signal_->notify();
}

Participant::Participant(const std::string& name, const DdsOptions& o) : o_(o) {
  dds::DomainParticipantQos q = participant_qos(name, o);
  if (!o.security_dir.empty()) {
    const SecureFiles files{o.security_dir};
    add_security_properties(q.properties(), files, name);
    learn_secure_identities(files);
  }
  dp_ = dds::DomainParticipantFactory::get_instance()->create_participant(o.domain, q);
  if (!dp_)
    throw std::runtime_error("cannot create DDS participant '" + name + "' on domain " +
                             std::to_string(o.domain));
  // Latched writers' acknowledgement locator (writer()); a participant with UDP data locators
  // needs none. Fast DDS moves a participant's ports when they are taken: only a port this
  // process holds is announced.
  if (o.shm && o.shm_data_only && !o.is_server) {
    const auto loc = metatraffic_udp_locator(o);
    if (loc && udp_port_bound_by(getpid(), static_cast<int>(loc->port))) latched_ack_ = loc;
  }
  pub_ = dp_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
  sub_ = dp_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
  if (!pub_ || !sub_) throw std::runtime_error("cannot create DDS publisher/subscriber for '" + name + "'");
}

namespace {
std::atomic<double> g_deletion_bound_s{0.0};
std::atomic<bool> g_left_open{false};

void delete_participant(dds::DomainParticipant* dp) {
  dp->delete_contained_entities();
  dds::DomainParticipantFactory::get_instance()->delete_participant(dp);
}
}  // namespace

void bound_participant_deletion(double seconds) { g_deletion_bound_s = seconds; }

bool participant_left_open() { return g_left_open.load(); }

Participant::~Participant() {
  if (!dp_) return;
  const double bound = g_deletion_bound_s.load();
  if (bound <= 0.0) {
    delete_participant(dp_);
    return;
  }
  // The deletion runs in a thread of its own so that a deadlock inside Fast DDS cannot hold
  // this one: the promise is shared, so a thread left running never touches freed memory.
  auto done = std::make_shared<std::promise<void>>();
  std::future<void> finished = done->get_future();
  std::thread t([dp = dp_, done] {
    delete_participant(dp);
    done->set_value();
  });
  if (finished.wait_for(std::chrono::duration<double>(bound)) == std::future_status::ready) {
    t.join();
    return;
  }
  t.detach();
  g_left_open = true;
}

dds::Topic* Participant::make_topic(const std::string& name, dds::TypeSupport& ts) {
  if (auto* existing = dynamic_cast<dds::Topic*>(dp_->lookup_topicdescription(name))) return existing;
  ts.register_type(dp_);  // a second registration of the same type is refused, and harmless
  dds::Topic* t = dp_->create_topic(name, ts.get_type_name(), dds::TOPIC_QOS_DEFAULT);
  if (!t) throw std::runtime_error("cannot create topic " + name);
  return t;
}

namespace {

std::string exe_dir() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string(".") : exe.parent_path().string();
}

/// Loads the profiles once: Fast DDS's own default file (FASTRTPS_DEFAULT_PROFILES_FILE or
/// ./DEFAULT_FASTRTPS_PROFILES.xml), and the shipped file unless the variable names another.
void load_qos_profiles() {
  static std::once_flag once;
  std::call_once(once, [] {
    auto* f = dds::DomainParticipantFactory::get_instance();
    f->load_profiles();
    if (std::getenv(kEnvQosProfiles)) return;
    const std::string file = qos_profiles_file();
    if (f->load_XML_profiles_file(file) != ReturnCode_t::RETCODE_OK)
      throw std::runtime_error("cannot load the DDS QoS profiles from " + file);
  });
}

const char* profile_name(Profile p, bool writer) {
  if (p == Profile::kStream) return writer ? "maptr_stream_writer" : "maptr_stream_reader";
  if (p == Profile::kReliableStream)
    return writer ? "maptr_reliable_stream_writer" : "maptr_reliable_stream_reader";
  return writer ? "maptr_latched_writer" : "maptr_latched_reader";
}

/// The QoS of profile `p` from the profiles file (loaded once): `get(name, qos)` is the
/// publisher's or subscriber's look-up. Throws when the file lacks the profile.
template <class Qos, class Get>
Qos profile_qos(Profile p, bool writer, Get get) {
  load_qos_profiles();
  Qos q;
  const char* name = profile_name(p, writer);
  if (get(name, q) != ReturnCode_t::RETCODE_OK)
    throw std::runtime_error(std::string("DDS QoS profile '") + name + "' not found in " +
                             qos_profiles_file());
  return q;
}

}  // namespace

std::string qos_profiles_file() {
  if (const char* f = std::getenv(kEnvQosProfiles)) return f;
  return exe_dir() + "/maptr_qos.xml";
}

dds::DataWriter* Participant::writer(dds::Topic* t, Profile p, dds::DataWriterListener* l,
                                     int32_t reader_filters) {
  auto q = profile_qos<dds::DataWriterQos>(p, true, [this](const char* n, dds::DataWriterQos& w) {
    return pub_->get_datawriter_qos_from_profile(n, w);
  });
  if (reader_filters > 0) {
    q.writer_resource_limits().reader_filters_allocation.initial = static_cast<size_t>(reader_filters);
    q.writer_resource_limits().reader_filters_allocation.maximum = static_cast<size_t>(reader_filters);
  }
  if (p == Profile::kLatched) add_latched_ack_locator(q);
  auto* w =
      pub_->create_datawriter(t, q, l, l ? dds::StatusMask::publication_matched() : dds::StatusMask::none());
  if (!w) throw std::runtime_error("cannot create writer on " + t->get_name());
  return w;
}

std::optional<rtps::Locator_t> metatraffic_udp_locator(const DdsOptions& o) {
  if (o.participant_id < 0) return std::nullopt;
  rtps::Locator_t loc;
  loc.kind = LOCATOR_KIND_UDPv4;
  rtps::IPLocator::setIPv4(loc, o.interface_address);
  loc.port = static_cast<uint32_t>(rtps_metatraffic_unicast_port(o.domain, o.participant_id));
  return loc;
}

void Participant::add_latched_ack_locator(dds::DataWriterQos& q) const {
  if (!latched_ack_) return;
  q.endpoint().unicast_locator_list.clear();
  q.endpoint().unicast_locator_list.push_back(*latched_ack_);
}

dds::DataReader* Participant::reader(dds::TopicDescription* t, Profile p, dds::DataReaderListener* l,
                                     int32_t depth) {
  auto q = profile_qos<dds::DataReaderQos>(p, false, [this](const char* n, dds::DataReaderQos& r) {
    return sub_->get_datareader_qos_from_profile(n, r);
  });
  if (depth > 0) {
    q.history().kind = dds::KEEP_LAST_HISTORY_QOS;
    q.history().depth = depth;
    q.resource_limits().max_samples = std::max(q.resource_limits().max_samples, depth);
    q.resource_limits().max_samples_per_instance = depth;
  }
  dds::StatusMask mask = dds::StatusMask::data_available()
                         << dds::StatusMask::subscription_matched() << dds::StatusMask::liveliness_changed();
  auto* r = sub_->create_datareader(t, q, l, mask);
  if (!r) throw std::runtime_error("cannot create reader on " + t->get_name());
  return r;
}

DdsOptions options_from_env() {
  DdsOptions o;
  if (const char* d = std::getenv(kEnvDomain)) o.domain = std::atoi(d);
  if (const char* s = std::getenv(kEnvDiscoveryServer)) o.discovery_server = s;
  if (const char* i = std::getenv(kEnvDiscoveryOwn)) o.own_server = std::atoi(i);
  if (const char* a = std::getenv(kEnvInterface)) o.interface_address = a;
  if (const char* l = std::getenv(kEnvLease)) o.lease_s = std::atof(l);
  if (const char* t = std::getenv(kEnvTransport)) {
    o.shm = std::string(t) != "udp";
    o.shm_data_only = std::string(t) == "shm";
  }
  if (const char* q = std::getenv(kEnvShmPortQueue)) o.shm_port_queue = static_cast<uint32_t>(std::atol(q));
  if (const char* id = std::getenv(kEnvParticipantId)) o.participant_id = std::atoi(id);
  if (const char* m = std::getenv(kEnvShmSegmentBytes))
    o.shm_segment_bytes = static_cast<uint32_t>(std::atol(m));
  if (const char* f = std::getenv(kEnvFleetId))
    o.fleet_id = static_cast<uint32_t>(std::strtoul(f, nullptr, 10));
  if (const char* s = std::getenv(kEnvSecurityDir)) o.security_dir = s;
  if (const char* l = std::getenv(kEnvDdsLog)) o.dds_log = l;
  return o;
}

namespace {

int run_fastdds_shm_clean() {
  // `fastdds shm clean` (fastdds-tools) removes the segments and ports whose owner is gone;
  // segments of live processes are kept.
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    // Only async-signal-safe calls between fork and exec (the parent has DDS threads).
    const int fd = open("/dev/null", O_WRONLY);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
    }
    execlp("fastdds", "fastdds", "shm", "clean", static_cast<char*>(nullptr));
    _exit(127);
  }
  // Bounded wait: a cleaner that hangs must not hang the caller.
  int status = 0;
  for (int i = 0; i < 300; ++i) {
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    usleep(20000);
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

int clean_stale_shm(const std::set<int>& own_ports) {
  run_fastdds_shm_clean();
  // Then the port files `fastdds shm clean` leaves (see comm/posix/shm_files.hpp).
  return remove_unused_shm_ports("/dev/shm", 10.0, own_ports).ports_removed;
}

}  // namespace maptr::comm
