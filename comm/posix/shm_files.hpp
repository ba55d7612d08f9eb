#pragma once
// Stale Fast DDS shared-memory port files. Pure POSIX (no DDS), so it can be tested on its own.
//
// Fast DDS keeps one shared-memory "port" per locator: `fastrtps_port<N>` (the ring buffer),
// `fastrtps_port<N>_el` (its lock file) and `sem.fastrtps_port<N>_mutex` (its named mutex).
// Ports are created by whichever participant first opens them, also by a sender to a port
// nobody listens on, and `fastdds shm clean` (2.9) does not count such ports as zombies, so
// every fleet leaves some behind. On one domain the same port numbers come back at every run:
// hundreds of leftovers were seen to make a later fleet's discovery fail.
#include <set>
#include <string>

namespace maptr::comm {

struct ShmSweep {
  int ports_removed = 0;         ///< port groups removed (each up to three files)
  int ports_in_use = 0;          ///< port groups kept: a process maps one of their files or locks its `_el`
  int ports_too_young = 0;       ///< port groups kept: a file was modified less than min_age_s ago
  int unreadable_processes = 0;  ///< processes whose /proc/PID/maps this user may not read
};

/// Removes the port groups in `dir` (normally /dev/shm) that belong to this user, that no
/// process maps, whose `_el` lock no process holds (the test `fastdds shm clean` makes; ports
/// that only senders opened have no `_el`, which is why it leaves them), and whose files were
/// not modified for `min_age_s` seconds (a port just being created is not mapped yet).
/// Processes whose maps this user may not read (another user's, or the container's init) are
/// not Fast DDS participants of this user, whose maps are always readable; they are counted.
/// `any_age`: port numbers removed without the age condition (a fleet's own ports, once all
/// its processes have ended); every other port still needs min_age_s.
ShmSweep remove_unused_shm_ports(const std::string& dir = "/dev/shm", double min_age_s = 10.0,
                                 const std::set<int>& any_age = {});

/// RTPS well-known port mapping (PB 7400, DG 250, PG 2; d0 0, d1 10, d2 1, d3 11), which Fast
/// DDS also uses to name its shared-memory ports. The first port of `domain`:
inline int rtps_domain_port_base(int domain) { return 7400 + 250 * domain; }
/// Participant `id`'s unicast ports on `domain`: metatraffic (d1) and user data (d3).
inline int rtps_metatraffic_unicast_port(int domain, int id) {
  return rtps_domain_port_base(domain) + 10 + 2 * id;
}
inline int rtps_user_unicast_port(int domain, int id) { return rtps_domain_port_base(domain) + 11 + 2 * id; }

/// The highest participant id whose ports on `domain` stay below 65536 (ids above about 120
/// already use the next domains' port ranges, which is fine).
inline int rtps_max_participant_id(int domain) { return (65535 - rtps_domain_port_base(domain) - 11) / 2; }

/// The port numbers of `domain` for participant ids 0..max_participant_id: the two multicast
/// ports of the domain, and for each id its metatraffic and user unicast ports.
std::set<int> rtps_ports(int domain, int max_participant_id);

}  // namespace maptr::comm
