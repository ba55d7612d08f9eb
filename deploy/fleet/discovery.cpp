#include "deploy/fleet/discovery.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <filesystem>
#include <stdexcept>
#include <thread>

namespace maptr::deploy::fleet {

namespace {
constexpr std::chrono::milliseconds kListenPoll{10};

sockaddr_in loopback(int port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<uint16_t>(port));
  return a;
}
}  // namespace

int free_udp_port() {
  int fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a = loopback(0);
  socklen_t len = sizeof(a);
  if (fd < 0 || bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0 ||
      getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
    if (fd >= 0) close(fd);
    throw std::runtime_error("cannot find a free UDP port on 127.0.0.1");
  }
  close(fd);
  return ntohs(a.sin_port);
}

bool udp_port_bound(int port) {
  int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return false;
  sockaddr_in a = loopback(port);
  const bool taken = bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0 && errno == EADDRINUSE;
  close(fd);
  return taken;
}

DiscoveryServer::DiscoveryServer(const std::string& binary, const std::string& run_dir, int domain,
                                 double listen_s, double restart_delay_s)
    : run_dir_(run_dir), port_(free_udp_port()), listen_s_(listen_s), restart_delay_s_(restart_delay_s) {
  address_ = "127.0.0.1:" + std::to_string(port_);
  c_.name = "discovery";
  c_.binary = binary;
  c_.args = {"--address", address_, "--domain", std::to_string(domain)};
  if (!std::filesystem::exists(binary)) throw std::runtime_error("missing process binary " + binary);
}

DiscoveryServer::~DiscoveryServer() {
  if (c_.running) kill(c_.pid, SIGKILL), waitpid(c_.pid, nullptr, 0);
}

bool DiscoveryServer::start(const Environment& env, ParticipantIds& ids) {
  spawn(c_, run_dir_, env, ids.take(0, restarts_));  // fresh ports after a restart
  const auto t0 = Clock::now();
  while (std::chrono::duration<double>(Clock::now() - t0).count() < listen_s_) {
    if (udp_port_bound(port_)) return true;
    int st = 0;
    if (waitpid(c_.pid, &st, WNOHANG) == c_.pid) {
      c_.running = false;
      return false;
    }
    std::this_thread::sleep_for(kListenPoll);
  }
  return false;
}

void DiscoveryServer::start_or_throw(const Environment& env, ParticipantIds& ids) {
  if (start(env, ids)) return;
  if (c_.running) kill(c_.pid, SIGKILL), waitpid(c_.pid, nullptr, 0);
  throw std::runtime_error("the discovery server did not start on " + address_ + " (see " + run_dir_ +
                           "/logs/discovery.stderr)");
}

bool DiscoveryServer::on_exit(const Exit& e, bool expected) {
  if (e.pid != c_.pid || !c_.running) return false;
  c_.running = false;
  if (!expected) {
    ++restarts_;
    restart_at_ = Clock::now() + std::chrono::milliseconds(static_cast<long>(1000 * restart_delay_s_));
  }
  return true;
}

bool DiscoveryServer::restart_if_due(const Environment& env, ParticipantIds& ids, bool& started) {
  if (!restart_at_ || Clock::now() < *restart_at_) return false;
  restart_at_.reset();
  started = start(env, ids);
  return true;
}

void DiscoveryServer::kill_now() {
  if (c_.running) kill(c_.pid, SIGKILL);
}

void DiscoveryServer::stop(double term_s) {
  if (!c_.running) return;
  stop_process(c_.pid, term_s);
  c_.running = false;
}

}  // namespace maptr::deploy::fleet
