// A latched (reliable, transient-local) writer of a participant whose user data is on shared
// memory only, and a reader that has UDP only and joins after the sample was written: the way
// `maptr top` joins a running fleet. The writer runs in a child process (this test binary run
// again on its DISABLED_ half), so nothing goes intraprocess; a discovery server in this process
// connects the two.
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <string>
#include <vector>

#include "comm/dds/dds.hpp"
#include "idl/maptrPubSubTypes.h"
#include "tests/bound_socket.hpp"

namespace maptr::comm {
namespace {

namespace dds = eprosima::fastdds::dds;

/// The writer's participant id (its metatraffic port takes the acknowledgements).
constexpr int kWriterParticipantId = 3;
/// Generous waits, s: discovery on a loaded machine takes seconds, not minutes.
constexpr double kWait_s = 60.0;

DdsOptions client_options(int domain, const std::string& server) {
  DdsOptions o;
  o.domain = domain;
  o.discovery_server = server;
  return o;
}

/// Membership events a reader received.
class Events : public dds::DataReaderListener {
 public:
  void on_data_available(dds::DataReader* r) override {
    msg::MembershipEvent e;
    dds::SampleInfo info;
    while (r->take_next_sample(&e, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      std::lock_guard<std::mutex> g(m_);
      names_.push_back(e.name());
      cv_.notify_all();
    }
  }
  bool wait_for_one(double s) {
    std::unique_lock<std::mutex> g(m_);
    return cv_.wait_for(g, std::chrono::duration<double>(s), [&] { return !names_.empty(); });
  }
  std::vector<std::string> names() {
    std::lock_guard<std::mutex> g(m_);
    return names_;
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  std::vector<std::string> names_;
};

/// Reads the child's standard output until a line `want` (true) or EOF / kWait_s (false).
bool read_until(int fd, const std::string& want, std::string& seen) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(kWait_s);
  char buf[512];
  while (seen.find(want + "\n") == std::string::npos) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd p{fd, POLLIN, 0};
    if (left.count() <= 0 || poll(&p, 1, static_cast<int>(left.count())) <= 0) return false;
    const ssize_t n = read(fd, buf, sizeof(buf));
    if (n <= 0) return false;
    seen.append(buf, static_cast<std::size_t>(n));
  }
  return true;
}

TEST(LatchedWriter, AUdpOnlyReaderThatJoinsLateGetsTheHistoryOfASharedMemoryWriter) {
  const int domain = 170 + static_cast<int>(getpid()) % 25;
  const int port = maptr::testing::BoundSocket().port;  // free a moment ago
  ASSERT_GT(port, 0);
  const std::string server = "127.0.0.1:" + std::to_string(port);
  DdsOptions so = client_options(domain, server);
  so.is_server = true;
  so.shm = false;
  Participant ds("latched-test-server", so);

  int to_child[2], from_child[2];
  ASSERT_EQ(pipe(to_child), 0);
  ASSERT_EQ(pipe(from_child), 0);
  const pid_t child = fork();
  if (child == 0) {
    dup2(to_child[0], STDIN_FILENO);
    dup2(from_child[1], STDOUT_FILENO);
    close(to_child[1]);
    close(from_child[0]);
    setenv("MAPTR_LATCHED_SERVER", server.c_str(), 1);
    setenv("MAPTR_LATCHED_DOMAIN", std::to_string(domain).c_str(), 1);
    execl("/proc/self/exe", "test_latched", "--gtest_filter=LatchedWriter.DISABLED_WriterInAChildProcess",
          "--gtest_also_run_disabled_tests", static_cast<char*>(nullptr));
    _exit(127);
  }
  close(to_child[0]);
  close(from_child[1]);
  std::string child_out;
  const bool written = read_until(from_child[0], "written", child_out);

  bool received = false;
  std::vector<std::string> names;
  if (written) {
    // Joins after the sample was written: the reader gets it from the writer's history only.
    DdsOptions ro = client_options(domain, server);
    ro.shm = false;  // as maptr top: UDP only
    Events events;  // outlives the participant, whose end still calls it
    Participant reader("latched-test-reader", ro);
    reader.reader(reader.topic<msg::MembershipEventPubSubType>(topic::kMembership), Profile::kLatched, &events);
    received = events.wait_for_one(kWait_s);
    names = events.names();
  }
  close(to_child[1]);  // the child ends when its standard input closes
  int st = -1;
  waitpid(child, &st, 0);
  std::string rest;
  read_until(from_child[0], "\x01never", rest);  // the rest of the child's output, to EOF
  close(from_child[0]);
  child_out += rest;

  ASSERT_TRUE(written) << "the writer process never wrote its sample:\n" << child_out;
  EXPECT_TRUE(received) << "the UDP-only reader that joined late never got the latched sample";
  EXPECT_EQ(names, std::vector<std::string>{"L3"});
  ASSERT_TRUE(WIFEXITED(st)) << child_out;
  EXPECT_EQ(WEXITSTATUS(st), 0) << child_out;
}

// Run only by the test above, in a fresh process: a fleet-like participant (a fixed id, user data
// on shared memory only) writes one latched sample, says "written", and stays until its standard
// input closes.
TEST(LatchedWriter, DISABLED_WriterInAChildProcess) {
  const char* server = std::getenv("MAPTR_LATCHED_SERVER");
  const char* domain = std::getenv("MAPTR_LATCHED_DOMAIN");
  ASSERT_TRUE(server && domain) << "run by AUdpOnlyReaderThatJoinsLateGetsTheHistoryOfASharedMemoryWriter";
  DdsOptions o = client_options(std::atoi(domain), server);
  o.shm = true;
  o.shm_data_only = true;
  o.participant_id = kWriterParticipantId;
  Participant p("latched-test-writer", o);
  auto* w = p.writer(p.topic<msg::MembershipEventPubSubType>(topic::kMembership), Profile::kLatched);
  // The writer takes acknowledgements on the participant's UDP metatraffic port.
  const auto& locators = w->get_qos().endpoint().unicast_locator_list;
  ASSERT_EQ(locators.size(), 1u);
  EXPECT_EQ(*locators.begin(), *metatraffic_udp_locator(o));
  msg::MembershipEvent e;
  e.seq(1);
  e.name("L3");
  e.kind(msg::MEMBER_DIED);
  ASSERT_EQ(w->write(&e), true);
  std::cout << "written" << std::endl;
  char c;
  while (read(STDIN_FILENO, &c, 1) > 0) {
  }
}

}  // namespace
}  // namespace maptr::comm
