#pragma once
// A UDP socket of the tests, bound to 127.0.0.1 on a port the kernel chooses.
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

namespace maptr::testing {

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
  BoundSocket(const BoundSocket&) = delete;
  BoundSocket& operator=(const BoundSocket&) = delete;
  int fd, port = 0;  ///< port 0: no socket
};

}  // namespace maptr::testing
