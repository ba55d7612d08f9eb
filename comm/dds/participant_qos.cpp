// The QoS of a participant from DdsOptions (comm/dds/participant_qos.hpp).
#include "comm/dds/participant_qos.hpp"

#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPFinder.h>
#include <fastrtps/utils/IPLocator.h>
#include <fastrtps/utils/md5.h>

#include <algorithm>
#include <cstdio>
#include <fastdds/dds/log/Log.hpp>
#include <memory>
#include <stdexcept>

#include "comm/dds/fleet_guid.hpp"
#include "comm/posix/environment.hpp"

namespace maptr::comm {

namespace dds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;

namespace {

rtps::Locator_t parse_locator(const std::string& addr) {
  const auto colon = addr.rfind(':');
  if (colon == std::string::npos)
    throw std::invalid_argument("discovery server '" + addr + "': expected HOST:PORT");
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
    for (const auto& l : ips)
      md5.update(reinterpret_cast<const unsigned char*>(l.address), sizeof(l.address));
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
    std::fprintf(stderr, "%s=%s: expected error, warning or info; Fast DDS's default kept\n", kEnvDdsLog,
                 level.c_str());
}

}  // namespace

namespace {

/// The lease and its announcements, and the discovery server(s) of a server or a client.
void set_discovery(dds::DomainParticipantQos& q, const DdsOptions& o) {
  auto& disc = q.wire_protocol().builtin.discovery_config;
  const long lease_ms = static_cast<long>(o.lease_s * 1000.0);
  disc.leaseDuration = eprosima::fastrtps::Duration_t(static_cast<int32_t>(lease_ms / 1000),
                                                      static_cast<uint32_t>((lease_ms % 1000) * 1000000));
  const long ann_ms = std::max(100L, lease_ms / 4);
  disc.leaseDuration_announcementperiod = eprosima::fastrtps::Duration_t(
      static_cast<int32_t>(ann_ms / 1000), static_cast<uint32_t>((ann_ms % 1000) * 1000000));

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
}

/// The transports: shared memory (data on this host) and UDP on one interface.
void set_transports(dds::DomainParticipantQos& q, const DdsOptions& o) {
  // Shared memory carries the data between processes on this host; UDP on one interface
  // (loopback, or the host's address on a fleet of several hosts) carries discovery and the
  // data to other hosts. Fast DDS uses a peer's shared-memory locator only when the peer
  // announces the same host id (a hash of the host name and the IPv4 addresses it sees).
  // A discovery server carries metatraffic only and talks UDP alone: with shared memory it would
  // reach each new client through that client's shared-memory port, which Fast DDS 2.9 opens only
  // after a health check that sleeps up to a third of a second unless the port's listener woke
  // since the last check, in the server's receive thread, one client after another (at 512
  // agents its UDP buffer overflowed meanwhile and discovery never completed; BENCHMARKS.md).
  q.transport().use_builtin_transports = false;
  if (o.shm && !o.is_server) {
    auto shm = std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>();
    if (o.shm_segment_bytes > 0) shm->segment_size(o.shm_segment_bytes);
    if (o.shm_port_queue > 0) shm->port_queue_capacity(o.shm_port_queue);
    q.transport().user_transports.push_back(shm);
    // Without this every sample would also go out on UDP (both transports select the reader).
    if (o.shm_data_only) q.wire_protocol().default_unicast_locator_list.push_back(shm_unicast_locator());
  }
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  udp->interfaceWhiteList.emplace_back(o.interface_address);
  if (o.udp_receive_buffer_bytes > 0) udp->receiveBufferSize = o.udp_receive_buffer_bytes;
  q.transport().user_transports.push_back(udp);
}

}  // namespace

dds::DomainParticipantQos participant_qos(const std::string& name, const DdsOptions& o) {
  set_dds_log_level(o.dds_log);
  dds::DomainParticipantQos q = dds::PARTICIPANT_QOS_DEFAULT;
  q.name(name);
  set_discovery(q, o);
  set_transports(q, o);
  if (o.participant_id >= 0) q.wire_protocol().participant_id = o.participant_id;
  if (o.fleet_id != 0 && o.participant_id >= 0 && !o.is_server)
    q.wire_protocol().prefix = fleet_guid_prefix(o.fleet_id, o.participant_id);
  return q;
}

}  // namespace maptr::comm
