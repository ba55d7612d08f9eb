// comm/udp_ports: ports read from /proc, never probed by binding.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "comm/posix/udp_ports.hpp"
#include "tests/bound_socket.hpp"

using maptr::testing::BoundSocket;

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
