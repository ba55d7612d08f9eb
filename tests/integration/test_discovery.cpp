// The launcher's discovery server (deploy/fleet/discovery.hpp) against a port another process
// takes between the launcher's choice and the server's bind.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>

#include "comm/posix/udp_ports.hpp"
#include "deploy/fleet/discovery.hpp"
#include "tests/integration/fleet_runner.hpp"

using maptr::comm::udp_port_bound_by;
using maptr::deploy::fleet::DiscoveryServer;
using maptr::deploy::fleet::ParticipantIds;
using maptr::testing::private_domain;
using maptr::testing::TempDir;

namespace {

/// A UDP socket bound to 127.0.0.1:port, closed on destruction (-1 if the bind failed).
struct Squatter {
  explicit Squatter(int port) : fd(socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = htons(static_cast<uint16_t>(port));
    if (bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0) close(fd), fd = -1;
  }
  ~Squatter() {
    if (fd >= 0) close(fd);
  }
  int fd;
};

}  // namespace

TEST(DiscoveryServer, APortTakenBeforeTheServerBindsItIsReplacedByAFreshOne) {
  TempDir tmp;
  std::filesystem::create_directories(tmp.path() + "/logs");
  DiscoveryServer ds(std::string(MAPTR_BIN_DIR) + "/maptr_discovery", tmp.path(), private_domain(), 30.0,
                     1.0);
  const int chosen = ds.port();
  Squatter squatter(chosen);
  ASSERT_GE(squatter.fd, 0) << "port " << chosen << " was taken before the test could take it";
  EXPECT_TRUE(udp_port_bound_by(getpid(), chosen));  // this process holds it
  ParticipantIds ids(4, 8);
  ds.start_or_throw({{"MAPTR_TRANSPORT", "shm"}}, ids);
  EXPECT_TRUE(ds.running());
  EXPECT_NE(ds.port(), chosen);
  EXPECT_EQ(ds.address(), "127.0.0.1:" + std::to_string(ds.port()));
  EXPECT_TRUE(udp_port_bound_by(ds.pid(), ds.port()));
  // The squatter's socket is listed in the server's namespace too, but it is not the server's.
  EXPECT_FALSE(udp_port_bound_by(ds.pid(), chosen));
  ds.stop(5.0);
  EXPECT_FALSE(ds.running());
}
