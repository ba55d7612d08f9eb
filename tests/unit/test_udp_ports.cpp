// comm/udp_ports: ports read from /proc, never probed by binding.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "comm/udp_ports.hpp"

namespace {

/// A UDP socket on 127.0.0.1 with a port the kernel chooses.
struct BoundSocket {
  BoundSocket() : fd(socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof(a);
    if (fd < 0 || bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0 ||
        getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0)
      return;
    port = ntohs(a.sin_port);
  }
  ~BoundSocket() {
    if (fd >= 0) close(fd);
  }
  int fd, port = 0;
};

}  // namespace

TEST(UdpPorts, ABoundPortIsListedAndIsThisProcesssUntilItIsClosed) {
  int port = 0;
  {
    BoundSocket s;
    ASSERT_GT(s.port, 0);
    port = s.port;
    EXPECT_TRUE(maptr::comm::udp_port_listed(port));
    EXPECT_TRUE(maptr::comm::udp_port_bound_by(getpid(), port));
    EXPECT_FALSE(maptr::comm::udp_port_bound_by(getppid(), port));  // listed there, but not its socket
  }
  EXPECT_FALSE(maptr::comm::udp_port_listed(port));
  EXPECT_FALSE(maptr::comm::udp_port_bound_by(getpid(), port));
}
