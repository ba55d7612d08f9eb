// The replayer child of `maptr top --run` on a finished run (deploy/top/replay_process): the
// free-domain probe against sockets bound as Fast DDS binds them, the command line and
// environment the replayer is started with, its exit code, and its end by PID.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "comm/posix/shm_files.hpp"
#include "deploy/top/replay_process.hpp"
#include "deploy/top/view_text.hpp"

using namespace maptr::top;

namespace {

/// The highest domain `maptr top` searches (the CLI's --domain range).
constexpr int kHighest = 232;

/// A UDP socket bound to `port` (SO_REUSEADDR, as Fast DDS binds its multicast ports); closed on
/// destruction.
class BoundPort {
 public:
  BoundPort(uint32_t address, int port) : fd_(socket(AF_INET, SOCK_DGRAM, 0)) {
    const int one = 1;
    setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr.s_addr = htonl(address);
    ok_ = bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof(a)) == 0;
  }
  ~BoundPort() { close(fd_); }
  bool ok() const { return ok_; }

 private:
  int fd_;
  bool ok_ = false;
};

/// A fresh folder, removed on destruction.
class Scratch {
 public:
  Scratch() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "maptr-replay-XXXXXX").string();
    path_ = mkdtemp(tmpl.data());
  }
  ~Scratch() { std::filesystem::remove_all(path_); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// An executable shell script `body` at `path`.
std::string script(const std::string& path, const std::string& body) {
  std::ofstream(path) << "#!/bin/sh\n" << body << "\n";
  std::filesystem::permissions(path, std::filesystem::perms::owner_all);
  return path;
}

bool wait_exit(ReplayProcess& p, double timeout_s) {
  const auto t0 = std::chrono::steady_clock::now();
  while (!p.exited()) {
    if (std::chrono::steady_clock::now() - t0 > std::chrono::duration<double>(timeout_s)) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

}  // namespace

TEST(TopReplay, ADomainWhoseMulticastPortIsHeldIsInUseAndSkipped) {
  const int d = free_domain(kHighest);
  EXPECT_FALSE(domain_in_use(d));
  BoundPort multicast(INADDR_ANY, maptr::comm::rtps_domain_port_base(d));
  ASSERT_TRUE(multicast.ok());
  EXPECT_TRUE(domain_in_use(d));
  EXPECT_LT(free_domain(d), d);
}

TEST(TopReplay, ADomainWithAParticipantsUnicastPortOnLoopbackIsInUse) {
  const int d = free_domain(kHighest);
  // Participant id 1's metatraffic unicast port: d0 + 2 * 1 + 10.
  BoundPort unicast(INADDR_LOOPBACK, maptr::comm::rtps_domain_port_base(d) + 12);
  ASSERT_TRUE(unicast.ok());
  EXPECT_TRUE(domain_in_use(d));
}

TEST(TopReplay, TheReplayerGetsTheRunDomainRateAndUdpOnlyAndItsExitCodeIsKept) {
  Scratch dir;
  const std::string seen = dir.path() + "/seen";
  const std::string fake =
      script(dir.path() + "/maptr", "echo \"$MAPTR_TRANSPORT $*\" > '" + seen + "'\nexit 3");
  ReplayProcess p(fake, "runs/old", 217, 2.5);
  ASSERT_TRUE(wait_exit(p, 30));
  EXPECT_EQ(p.exit_code(), 3);
  std::ifstream in(seen);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "udp replay runs/old --domain 217 --rate 2.5 --wait-reader " +
                      std::to_string(kReplayWaitReader_s) + " --quiet");
}

TEST(TopReplay, AReplayerStillRunningIsEndedByItsPidWhenTheWatchEnds) {
  Scratch dir;
  const std::string fake = script(dir.path() + "/maptr", "exec sleep 600");
  pid_t pid = -1;
  {
    ReplayProcess p(fake, "runs/old", 217, 1.0);
    pid = p.pid();
    EXPECT_FALSE(p.exited());
  }
  // Ended and reaped: no child of ours has that PID any more.
  errno = 0;
  EXPECT_EQ(waitpid(pid, nullptr, WNOHANG), -1);
  EXPECT_EQ(errno, ECHILD);
}

TEST(TopReplay, TheHeaderOfAReplayNamesItsRate) {
  RunInfo info{"default", "runs/old", 16, 10.0, 231};
  info.replay_rate = 2;
  const auto lines = layout(FleetView(info), 80, 0);
  EXPECT_NE(lines.at(0).find("domain 231  replay 2x"), std::string::npos) << lines.at(0);
  info.replay_rate = 0;
  EXPECT_EQ(layout(FleetView(info), 80, 0).at(0).find("replay"), std::string::npos);
}
