#include "deploy/fleet/zygote_client.hpp"

#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <thread>

#include "comm/posix/zygote.hpp"

namespace maptr::deploy::fleet {

namespace {
constexpr int kReplyTimeoutS = 10;  // a fork and a wait for the middle process: milliseconds
constexpr auto kEndWait = std::chrono::seconds(3);
}  // namespace

std::unique_ptr<Zygote> Zygote::start(const std::string& binary, const std::vector<std::string>& env,
                                      const std::string& out_path) {
  // Copies the zygote forks become this process's children when their middle process exits.
  if (prctl(PR_SET_CHILD_SUBREAPER, 1) != 0) return nullptr;
  int sv[2];
  if (socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, sv) != 0) return nullptr;
  const pid_t pid = start_process({binary, comm::kZygoteFlag, std::to_string(kPassedFd)}, env, out_path, sv[1]);
  close(sv[1]);
  if (pid < 0) {
    close(sv[0]);
    return nullptr;
  }
  timeval tv{kReplyTimeoutS, 0};
  setsockopt(sv[0], SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  setsockopt(sv[0], SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
  return std::unique_ptr<Zygote>(new Zygote(binary, sv[0], pid));
}

pid_t Zygote::fork_copy(const std::vector<std::string>& argv, const std::vector<std::string>& env,
                        const std::string& out_path) {
  if (fd_ < 0) return -1;
  comm::ZygoteRequest r{argv, env, out_path, getpid()};
  const std::string m = comm::encode_zygote_request(r);
  int32_t v = -1;
  if (send(fd_, m.data(), m.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(m.size()) ||
      recv(fd_, &v, sizeof v, 0) != static_cast<ssize_t>(sizeof v)) {
    drop();  // gone, or not answering: the request's fate is unknown, so the zygote is not used again
    ++failed_;
    return -1;
  }
  if (v <= 0) {
    ++failed_;
    return -1;
  }
  ++forked_;
  return static_cast<pid_t>(v);
}

void Zygote::lost() {
  reaped_ = true;
  drop();
}

void Zygote::drop() {
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
}

Zygote::~Zygote() {
  drop();  // end of its input: it returns from serve_zygote
  if (reaped_ || pid_ <= 0) return;
  const auto until = std::chrono::steady_clock::now() + kEndWait;
  for (;;) {
    const pid_t r = waitpid(pid_, nullptr, WNOHANG);
    if (r == pid_ || (r < 0 && errno == ECHILD)) return;  // ended (or reaped elsewhere)
    if (std::chrono::steady_clock::now() > until) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(pid_, SIGKILL);
  waitpid(pid_, nullptr, 0);
}

}  // namespace maptr::deploy::fleet
