#include "deploy/fleet/discovery.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "comm/dds/dds.hpp"
#include "comm/posix/udp_ports.hpp"
#include "deploy/fleet/hosts.hpp"

namespace maptr::deploy::fleet {

namespace {
constexpr std::chrono::milliseconds kListenPoll{10};
/// Ports tried by the server of a fleet on one host before the launch gives up.
constexpr int kStartAttempts = 3;
/// Discovery port of the servers of a fleet on several hosts: this plus the domain id.
constexpr int kHostDiscoveryPortBase = 11811;

sockaddr_in loopback(int port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<uint16_t>(port));
  return a;
}
/// The last non-empty line of a log file ("no output" if there is none).
std::string last_line(const std::string& path) {
  std::ifstream f(path);
  std::string line, last = "no output";
  while (std::getline(f, line))
    if (!line.empty()) last = line;
  return last;
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

int host_discovery_port(int domain) { return kHostDiscoveryPortBase + domain; }

DiscoveryServer::DiscoveryServer(const std::string& binary, const std::string& run_dir, int domain,
                                 double listen_s, double restart_delay_s, const std::string& servers,
                                 int index, const Child& host_like, bool netns)
    : run_dir_(run_dir),
      domain_(domain),
      port_(host_discovery_port(domain)),
      listen_s_(listen_s),
      restart_delay_s_(restart_delay_s),
      index_(index),
      count_(static_cast<int>(comm::split_servers(servers).size())),
      netns_(netns),
      remote_(!netns ||
              is_ssh_prefix(host_like.prefix)) {  // over ssh: not a process of this machine to watch
  address_ = comm::split_servers(servers).at(static_cast<std::size_t>(index));
  c_.name = "discovery-h" + std::to_string(index);
  c_.binary = binary;
  c_.args = {"--address", servers, "--index", std::to_string(index), "--domain", std::to_string(domain)};
  c_.host = host_like.host;
  c_.prefix = host_like.prefix;
  c_.host_env = host_like.host_env;
  if (!std::filesystem::exists(binary)) throw std::runtime_error("missing process binary " + binary);
}

DiscoveryServer::DiscoveryServer(const std::string& binary, const std::string& run_dir, int domain,
                                 double listen_s, double restart_delay_s)
    : run_dir_(run_dir), domain_(domain), listen_s_(listen_s), restart_delay_s_(restart_delay_s) {
  c_.name = "discovery";
  c_.binary = binary;
  use_port(free_udp_port());
  if (!std::filesystem::exists(binary)) throw std::runtime_error("missing process binary " + binary);
}

void DiscoveryServer::use_port(int port) {
  port_ = port;
  address_ = "127.0.0.1:" + std::to_string(port);
  c_.args = {"--address", address_, "--domain", std::to_string(domain_)};
}

DiscoveryServer::~DiscoveryServer() {
  if (c_.running) kill(c_.pid, SIGKILL), waitpid(c_.pid, nullptr, 0);
}

bool DiscoveryServer::start(const Environment& env, ParticipantIds& ids) {
  // Fresh ports after a restart; each server of a fleet on several hosts its own id (their
  // shared-memory ports share /dev/shm).
  spawn(c_, run_dir_, env, ids.take(0, index_ + count_ * restarts_));
  if (remote_) return true;  // a real machine: the clients retry until it answers
  const auto t0 = Clock::now();
  while (std::chrono::duration<double>(Clock::now() - t0).count() < listen_s_) {
    // Read from /proc, never probed by binding: a probe holding the port for a moment makes the
    // server's own bind fail ("wasn't able to allocate the specified listening port").
    // Before its exec the child still holds what it inherited: the process must be the server.
    if (runs_binary(c_.pid, c_.binary) && comm::udp_port_bound_by(c_.pid, port_)) return true;
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
  // The server of a fleet on one host takes a port found free a moment before; another process
  // may take it in between. Such a server exits at once, and a fresh port is tried.
  const bool own_port = count_ == 1 && !netns_ && !remote_;
  for (int attempt = 1;; ++attempt) {
    if (start(env, ids)) return;
    const bool exited = !c_.running;
    if (c_.running) kill(c_.pid, SIGKILL), waitpid(c_.pid, nullptr, 0);
    c_.running = false;
    if (!own_port || !exited || attempt >= kStartAttempts) break;
    use_port(free_udp_port());
  }
  throw std::runtime_error("the discovery server did not start on " + address_ + ": " +
                           last_line(run_dir_ + "/logs/" + c_.name + ".stderr") + " (see " + run_dir_ +
                           "/logs/" + c_.name + ".stderr)");
}

bool DiscoveryServer::on_exit(const Exit& e, bool expected) {
  if (e.pid != c_.pid || !c_.running) return false;
  c_.running = false;
  if (!expected && !held_) {
    ++restarts_;
    restart_at_ = Clock::now() + std::chrono::milliseconds(static_cast<long>(1000 * restart_delay_s_));
  }
  return true;
}

void DiscoveryServer::hold() {
  held_ = true;
  restart_at_.reset();
}

void DiscoveryServer::release() {
  held_ = false;
  if (c_.running) return;
  ++restarts_;
  restart_at_ = Clock::now();
}

bool DiscoveryServer::restart_if_due(const Environment& env, ParticipantIds& ids, bool& started) {
  if (held_ || !restart_at_ || Clock::now() < *restart_at_) return false;
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
