#include "deploy/top/replay_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <thread>
#include <vector>

#include "comm/posix/environment.hpp"
#include "comm/posix/shm_files.hpp"
#include "comm/posix/udp_ports.hpp"

extern char** environ;

namespace maptr::top {

namespace {

/// Participant ids probed: every process of a fleet or replay on the domain holds the lowest ones.
constexpr int kProbedIds = 4;
constexpr auto kReapPoll = std::chrono::milliseconds(20);

}  // namespace

bool domain_in_use(int domain) {
  if (comm::udp_port_listed(comm::rtps_domain_port_base(domain))) return true;  // simple-discovery multicast
  for (int id = 0; id < kProbedIds; ++id)
    if (comm::udp_port_listed(comm::rtps_metatraffic_unicast_port(domain, id)) ||
        comm::udp_port_listed(comm::rtps_user_unicast_port(domain, id)))
      return true;
  return false;
}

int free_domain(int highest) {
  for (int d = highest; d >= kLowestReplayDomain; --d)
    if (!domain_in_use(d)) return d;
  throw std::runtime_error("no free DDS domain between " + std::to_string(kLowestReplayDomain) + " and " +
                           std::to_string(highest));
}

ReplayProcess::ReplayProcess(const std::string& maptr, const std::string& run_dir, int domain, double rate) {
  // Everything the child needs is prepared before fork(): between fork and exec the child of a
  // multi-threaded process may only make async-signal-safe calls.
  char rate_text[32];
  std::snprintf(rate_text, sizeof(rate_text), "%.15g", rate);
  std::vector<std::string> args = {maptr,
                                   "replay",
                                   run_dir,
                                   "--domain",
                                   std::to_string(domain),
                                   "--rate",
                                   rate_text,
                                   "--wait-reader",
                                   std::to_string(kReplayWaitReader_s),
                                   "--quiet"};
  std::vector<std::string> env_store;
  for (char** e = environ; *e; ++e)
    if (std::string(*e).rfind(std::string(comm::kEnvTransport) + "=", 0) != 0) env_store.push_back(*e);
  env_store.push_back(std::string(comm::kEnvTransport) + "=udp");
  std::vector<char*> argv, envp;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  for (auto& e : env_store) envp.push_back(e.data());
  envp.push_back(nullptr);
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ < 0) throw std::runtime_error("cannot start maptr replay (fork failed)");
  if (pid_ == 0) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);  // UDP only: a killed replayer leaves no file behind
    if (getppid() != parent) _exit(1);
    setpgid(0, 0);  // a Ctrl-C in the terminal reaches maptr top only; it ends the replay
    const int fd = open("/dev/null", O_RDWR);
    if (fd >= 0) {
      dup2(fd, 0);
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    execve(argv[0], argv.data(), envp.data());
    _exit(127);
  }
}

ReplayProcess::~ReplayProcess() {
  if (exited()) return;
  kill(pid_, SIGTERM);
  const auto t0 = std::chrono::steady_clock::now();
  while (!exited()) {
    if (std::chrono::steady_clock::now() - t0 > std::chrono::duration<double>(kStopGrace_s)) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
      reaped_ = true;
      return;
    }
    std::this_thread::sleep_for(kReapPoll);
  }
}

bool ReplayProcess::exited() {
  if (reaped_) return true;
  int st = 0;
  if (waitpid(pid_, &st, WNOHANG) != pid_) return false;
  reaped_ = true;
  exit_code_ = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return true;
}

}  // namespace maptr::top
