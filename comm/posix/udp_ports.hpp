#pragma once
// UDP ports of this host, read from /proc (pure POSIX, no DDS). Nothing here binds a port to
// test it: a probe that holds a port for a moment can make the bind of a participant starting
// at that moment fail.
#include <sys/types.h>

namespace maptr::comm {

/// True when some socket of the calling process's network namespace is bound to UDP `port`, on
/// any local address, IPv4 or IPv6 (/proc/self/net/udp and udp6).
bool udp_port_listed(int port);

/// True once process `pid` itself holds a UDP socket bound to `port` (in its network
/// namespace): a socket of /proc/PID/net/udp on that port whose inode one of PID's descriptors
/// links to.
bool udp_port_bound_by(pid_t pid, int port);

}  // namespace maptr::comm
