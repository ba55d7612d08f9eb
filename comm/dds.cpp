#include "comm/dds.hpp"

#include "comm/fleet_guid.hpp"
#include "comm/security.hpp"
#include "comm/shm_files.hpp"
#include "comm/udp_ports.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/log/Log.hpp>
#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPFinder.h>
#include <fastrtps/utils/IPLocator.h>
#include <fastrtps/utils/md5.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

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

namespace {

rtps::Locator_t parse_locator(const std::string& addr) {
  const auto colon = addr.rfind(':');
  if (colon == std::string::npos) throw std::invalid_argument("discovery server '" + addr + "': expected HOST:PORT");
  rtps::Locator_t loc;
  loc.kind = LOCATOR_KIND_UDPv4;
  rtps::IPLocator::setIPv4(loc, addr.substr(0, colon));
  loc.port = static_cast<uint32_t>(std::stoul(addr.substr(colon + 1)));
  return loc;
}

rtps::GuidPrefix_t server_prefix(int index) {
  rtps::GuidPrefix_t p;
  eprosima::fastdds::rtps::get_server_client_default_guidPrefix(index, p);
  return p;
}

rtps::RemoteServerAttributes remote_server(const std::string& address, int index) {
  rtps::RemoteServerAttributes server;
  server.guidPrefix = server_prefix(index);
  server.metatrafficUnicastLocatorList.push_back(parse_locator(address));
  return server;
}

}  // namespace

rtps::Locator_t shm_unicast_locator() {
  // Fast DDS names this host's shared-memory locators by a 16-bit host id: the MD5 of the
  // addresses of its IPv4 interfaces, folded by XOR of big-endian 16-bit words (127.0.0.1 packed
  // little-endian when there is no interface). A locator with another id is not local to it.
  rtps::LocatorList_t ips;
  rtps::IPFinder::getIP4Address(&ips);
  uint16_t id = 0;
  if (ips.size() > 0) {
    ::MD5 md5;
    for (const auto& l : ips) md5.update(reinterpret_cast<const unsigned char*>(l.address), sizeof(l.address));
    md5.finalize();
    for (std::size_t i = 0; i < sizeof(md5.digest); i += 2)
      id ^= static_cast<uint16_t>((static_cast<uint16_t>(md5.digest[i]) << 8) | md5.digest[i + 1]);
  } else {
    reinterpret_cast<uint8_t*>(&id)[0] = 127;
    reinterpret_cast<uint8_t*>(&id)[1] = 1;
  }
  rtps::Locator_t loc(LOCATOR_KIND_SHM, 0);
  loc.address[0] = 'U';
  loc.address[1] = static_cast<rtps::octet>(id);
  loc.address[2] = static_cast<rtps::octet>(id >> 8);
  return loc;
}

std::vector<std::string> split_servers(const std::string& list) {
  std::vector<std::string> out;
  std::size_t from = 0;
  while (from <= list.size()) {
    const std::size_t comma = std::min(list.find(',', from), list.size());
    if (comma > from) out.push_back(list.substr(from, comma - from));
    from = comma + 1;
  }
  return out;
}

namespace {

/// Fast DDS's log level from MAPTR_DDS_LOG (DdsOptions::dds_log); an unknown level is said on stderr.
void set_dds_log_level(const std::string& level) {
  using eprosima::fastdds::dds::Log;
  if (level.empty()) return;
  if (level == "error")
    Log::SetVerbosity(Log::Error);
  else if (level == "warning")
    Log::SetVerbosity(Log::Warning);
  else if (level == "info")
    Log::SetVerbosity(Log::Info);
  else
    std::fprintf(stderr, "MAPTR_DDS_LOG=%s: expected error, warning or info; Fast DDS's default kept\n", level.c_str());
}

}  // namespace

Participant::Participant(const std::string& name, const DdsOptions& o) : o_(o) {
  set_dds_log_level(o.dds_log);
  dds::DomainParticipantQos q = dds::PARTICIPANT_QOS_DEFAULT;
  q.name(name);
  auto& disc = q.wire_protocol().builtin.discovery_config;
  const long lease_ms = static_cast<long>(o.lease_s * 1000.0);
  disc.leaseDuration = eprosima::fastrtps::Duration_t(static_cast<int32_t>(lease_ms / 1000),
                                        static_cast<uint32_t>((lease_ms % 1000) * 1000000));
  const long ann_ms = std::max(100L, lease_ms / 4);
  disc.leaseDuration_announcementperiod =
      eprosima::fastrtps::Duration_t(static_cast<int32_t>(ann_ms / 1000), static_cast<uint32_t>((ann_ms % 1000) * 1000000));

  // Several servers (one per host of a fleet on several hosts): each server connects to the
  // others, and a client registers with its own host's server only (own_server). A server
  // tracks the lease of the clients registered with it, and a server that a partition cut off
  // would, after the heal, announce as gone every client of the other hosts whose lease ran out
  // meanwhile; those are then unmatched everywhere although they never stopped.
  const std::vector<std::string> servers = split_servers(o.discovery_server);
  if (o.is_server) {
    if (o.server_index < 0 || o.server_index >= static_cast<int>(servers.size()))
      throw std::invalid_argument("discovery server address missing");
    disc.discoveryProtocol = rtps::DiscoveryProtocol_t::SERVER;
    q.wire_protocol().prefix = server_prefix(o.server_index);
    q.wire_protocol().builtin.metatrafficUnicastLocatorList.push_back(
        parse_locator(servers[static_cast<std::size_t>(o.server_index)]));
    for (std::size_t i = 0; i < servers.size(); ++i)
      if (static_cast<int>(i) != o.server_index)
        disc.m_DiscoveryServers.push_back(remote_server(servers[i], static_cast<int>(i)));
  } else if (!servers.empty()) {
    disc.discoveryProtocol = rtps::DiscoveryProtocol_t::CLIENT;
    for (std::size_t i = 0; i < servers.size(); ++i)
      if (o.own_server < 0 || o.own_server == static_cast<int>(i))
        disc.m_DiscoveryServers.push_back(remote_server(servers[i], static_cast<int>(i)));
    if (disc.m_DiscoveryServers.empty()) throw std::invalid_argument("discovery server index out of range");
  }
  if (!servers.empty() && (!o.is_server || servers.size() > 1))
    disc.discoveryServer_client_syncperiod = eprosima::fastrtps::Duration_t(0, 250 * 1000000);
  // Shared memory carries the data between processes on this host; UDP on one interface
  // (loopback, or the host's address on a fleet of several hosts) carries discovery and the
  // data to other hosts. Fast DDS uses a peer's shared-memory locator only when the peer
  // announces the same host id (a hash of the host name and the IPv4 addresses it sees).
  q.transport().use_builtin_transports = false;
  if (o.shm) {
    auto shm = std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>();
    if (o.shm_segment_bytes > 0) shm->segment_size(o.shm_segment_bytes);
    if (o.shm_port_queue > 0) shm->port_queue_capacity(o.shm_port_queue);
    q.transport().user_transports.push_back(shm);
    // Without this every sample would also go out on UDP (both transports select the reader).
    if (o.shm_data_only) q.wire_protocol().default_unicast_locator_list.push_back(shm_unicast_locator());
  }
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  udp->interfaceWhiteList.emplace_back(o.interface_address);
  q.transport().user_transports.push_back(udp);

  if (o.participant_id >= 0) q.wire_protocol().participant_id = o.participant_id;
  if (o.fleet_id != 0 && o.participant_id >= 0 && !o.is_server)
    q.wire_protocol().prefix = fleet_guid_prefix(o.fleet_id, o.participant_id);
  if (!o.security_dir.empty()) {
    const SecureFiles files{o.security_dir};
    add_security_properties(q.properties(), files, name);
    learn_secure_identities(files);
  }
  dp_ = dds::DomainParticipantFactory::get_instance()->create_participant(o.domain, q);
  if (!dp_) throw std::runtime_error("cannot create DDS participant '" + name + "' on domain " + std::to_string(o.domain));
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
    if (std::getenv("FASTRTPS_DEFAULT_PROFILES_FILE")) return;
    const std::string file = qos_profiles_file();
    if (f->load_XML_profiles_file(file) != ReturnCode_t::RETCODE_OK)
      throw std::runtime_error("cannot load the DDS QoS profiles from " + file);
  });
}

const char* profile_name(Profile p, bool writer) {
  if (p == Profile::kStream) return writer ? "maptr_stream_writer" : "maptr_stream_reader";
  if (p == Profile::kReliableStream) return writer ? "maptr_reliable_stream_writer" : "maptr_reliable_stream_reader";
  return writer ? "maptr_latched_writer" : "maptr_latched_reader";
}

std::runtime_error missing_profile(const char* name) {
  return std::runtime_error(std::string("DDS QoS profile '") + name + "' not found in " + qos_profiles_file());
}

}  // namespace

std::string qos_profiles_file() {
  if (const char* f = std::getenv("FASTRTPS_DEFAULT_PROFILES_FILE")) return f;
  return exe_dir() + "/maptr_qos.xml";
}

dds::DataWriter* Participant::writer(dds::Topic* t, Profile p, dds::DataWriterListener* l) {
  return writer(t, p, l, 0);
}

dds::DataWriter* Participant::writer(dds::Topic* t, Profile p, dds::DataWriterListener* l, int32_t reader_filters) {
  load_qos_profiles();
  dds::DataWriterQos q;
  if (pub_->get_datawriter_qos_from_profile(profile_name(p, true), q) != ReturnCode_t::RETCODE_OK)
    throw missing_profile(profile_name(p, true));
  if (reader_filters > 0) {
    q.writer_resource_limits().reader_filters_allocation.initial = static_cast<size_t>(reader_filters);
    q.writer_resource_limits().reader_filters_allocation.maximum = static_cast<size_t>(reader_filters);
  }
  if (p == Profile::kLatched) add_latched_ack_locator(q);
  auto* w = pub_->create_datawriter(t, q, l, l ? dds::StatusMask::publication_matched() : dds::StatusMask::none());
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

dds::DataReader* Participant::reader(dds::TopicDescription* t, Profile p, dds::DataReaderListener* l) {
  return reader(t, p, l, 0);
}

dds::DataReader* Participant::reader(dds::TopicDescription* t, Profile p, dds::DataReaderListener* l, int32_t depth) {
  load_qos_profiles();
  dds::DataReaderQos q;
  if (sub_->get_datareader_qos_from_profile(profile_name(p, false), q) != ReturnCode_t::RETCODE_OK)
    throw missing_profile(profile_name(p, false));
  if (depth > 0) {
    q.history().kind = dds::KEEP_LAST_HISTORY_QOS;
    q.history().depth = depth;
    q.resource_limits().max_samples = std::max(q.resource_limits().max_samples, depth);
    q.resource_limits().max_samples_per_instance = depth;
  }
  dds::StatusMask mask = dds::StatusMask::data_available() << dds::StatusMask::subscription_matched()
                         << dds::StatusMask::liveliness_changed();
  auto* r = sub_->create_datareader(t, q, l, mask);
  if (!r) throw std::runtime_error("cannot create reader on " + t->get_name());
  return r;
}

DdsOptions options_from_env() {
  DdsOptions o;
  if (const char* d = std::getenv("MAPTR_DOMAIN")) o.domain = std::atoi(d);
  if (const char* s = std::getenv("MAPTR_DISCOVERY_SERVER")) o.discovery_server = s;
  if (const char* i = std::getenv("MAPTR_DISCOVERY_INDEX")) o.server_index = std::atoi(i);
  if (const char* i = std::getenv("MAPTR_DISCOVERY_OWN")) o.own_server = std::atoi(i);
  if (const char* a = std::getenv("MAPTR_INTERFACE")) o.interface_address = a;
  if (const char* l = std::getenv("MAPTR_LEASE_S")) o.lease_s = std::atof(l);
  if (const char* t = std::getenv("MAPTR_TRANSPORT")) {
    o.shm = std::string(t) != "udp";
    o.shm_data_only = std::string(t) == "shm";
  }
  if (const char* q = std::getenv("MAPTR_SHM_PORT_QUEUE")) o.shm_port_queue = static_cast<uint32_t>(std::atol(q));
  if (const char* id = std::getenv("MAPTR_PARTICIPANT_ID")) o.participant_id = std::atoi(id);
  if (const char* m = std::getenv("MAPTR_SHM_SEGMENT_BYTES")) o.shm_segment_bytes = static_cast<uint32_t>(std::atol(m));
  if (const char* f = std::getenv("MAPTR_FLEET_ID")) o.fleet_id = static_cast<uint32_t>(std::strtoul(f, nullptr, 10));
  if (const char* s = std::getenv("MAPTR_SECURITY_DIR")) o.security_dir = s;
  if (const char* l = std::getenv("MAPTR_DDS_LOG")) o.dds_log = l;
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
  // Then the port files `fastdds shm clean` leaves (see comm/shm_files.hpp).
  return remove_unused_shm_ports("/dev/shm", 10.0, own_ports).ports_removed;
}

}  // namespace maptr::comm
