#include "deploy/fleet/children.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "comm/posix/environment.hpp"
#include "deploy/fleet/hosts.hpp"
#include "deploy/fleet/zygote_client.hpp"

extern char** environ;

namespace maptr::deploy::fleet {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
constexpr std::chrono::milliseconds kEndPoll{20};
constexpr std::chrono::milliseconds kStopPoll{10};

// A child is started with clone(CLONE_VM | CLONE_VFORK), as posix_spawn does, not with fork():
// the launcher's address space (its DDS participant, the recorder's queues) is not copied, so
// neither the launcher nor the child pays for the copy of its page tables, the copy-on-write
// faults that follow (each with a TLB shoot-down on the launcher's other threads' core) and the
// unmapping of the copy at exec (docs/bench/HISTORY.md, "The launcher starts its children without
// copying itself"). posix_spawn itself cannot set the parent-death signal. The child shares the
// launcher's memory until exec, so it makes system calls only, and no signal handler of the
// launcher runs in it: all signals stay blocked until its handlers are reset to the default.
struct ChildStart {
  char** argv;
  char** envp;
  const char* err_path;
  pid_t parent;
  int pass_fd;    // >= 0: handed to the child as its descriptor kPassedFd
  sigset_t mask;  // the launcher thread's signal mask, restored in the child before exec
};

int child_main(void* arg) {
  const auto* s = static_cast<const ChildStart*>(arg);
  for (int sig = 1; sig < NSIG; ++sig) {
    struct sigaction sa {};
    if (sigaction(sig, nullptr, &sa) != 0) continue;
    const bool handled = (sa.sa_flags & SA_SIGINFO) != 0 || (sa.sa_handler != SIG_DFL && sa.sa_handler != SIG_IGN);
    if (!handled) continue;
    sa.sa_handler = SIG_DFL;
    sa.sa_flags = 0;
    sigaction(sig, &sa, nullptr);
  }
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != s->parent) _exit(1);
  setpgid(0, 0);  // a Ctrl-C in the terminal reaches the launcher only; it ends the children
  const int in =
      open("/dev/null", O_RDONLY);  // never the launcher's terminal (it would stop a background reader)
  if (in >= 0) {
    dup2(in, 0);
    close(in);
  }
  const int fd = open(s->err_path, O_WRONLY | O_CREAT | O_APPEND, 0644);
  if (fd >= 0) {
    dup2(fd, 1);
    dup2(fd, 2);
    close(fd);
  }
  if (s->pass_fd >= 0 && dup2(s->pass_fd, kPassedFd) < 0) _exit(126);  // dup2 clears close-on-exec
  sigprocmask(SIG_SETMASK, &s->mask, nullptr);
  execvpe(s->argv[0], s->argv, s->envp);
  _exit(127);
}

pid_t start_child(ChildStart& s) {
  // The child runs on a stack of its own; the launcher's thread waits (CLONE_VFORK) until the
  // child has called exec or exited, so the stack and `s` outlive the child's use of them.
  static thread_local std::vector<char> stack(256 * 1024);
  sigset_t all;
  sigfillset(&all);
  pthread_sigmask(SIG_BLOCK, &all, &s.mask);
  const pid_t pid = clone(child_main, stack.data() + stack.size(), CLONE_VM | CLONE_VFORK | SIGCHLD, &s);
  pthread_sigmask(SIG_SETMASK, &s.mask, nullptr);
  return pid;
}
}  // namespace

Exit exit_of(pid_t pid, int st, long max_rss_kB) {
  return {pid, WIFEXITED(st) ? WEXITSTATUS(st) : -1, WIFSIGNALED(st) ? WTERMSIG(st) : 0, max_rss_kB};
}

void record_exit(Child& c, const Exit& e) {
  c.running = false;
  c.paused = false;
  c.exit_code = e.exit_code;
  c.signal = e.signal;
  c.max_rss_kB = std::max(c.max_rss_kB, e.max_rss_kB);
}

bool ended_cleanly(const Child& c) { return c.exit_code == 0 && c.signal == 0; }

std::string describe_end(const Child& c, const std::string& run_dir) {
  std::string out = c.name + (c.signal != 0 ? " was killed by signal " + std::to_string(c.signal)
                                            : " exited " + std::to_string(c.exit_code));
  // The last "critical" or "error" line of its log says why (spdlog: "... [NAME] critical: text").
  std::ifstream log(run_dir + "/logs/" + c.name + ".log");
  std::string why;
  for (std::string line; std::getline(log, line);)
    for (const char* level : {"] critical: ", "] error: "})
      if (const auto at = line.find(level); at != std::string::npos) why = line.substr(at + std::strlen(level));
  return why.empty() ? out : out + ": " + why;
}

namespace {
/// What the launcher sets for c: env, c.host_env and MAPTR_PARTICIPANT_ID; for a process on a
/// host (a command prefix: over ssh it gets nothing else), also the user's own settings of
/// comm/posix/environment.hpp that this launcher has, but a folder of this machine's session.
Environment own_environment(const Child& c, const Environment& env, int participant_id) {
  Environment own;
  if (!c.prefix.empty())
    for (const auto& v : comm::kEnvironment)
      if (std::string(v.set_by).rfind("user", 0) == 0 && std::string(v.name) != comm::kEnvRuntimeDir)
        if (const char* value = std::getenv(v.name)) own[v.name] = value;
  for (const auto& [k, v] : env) own[k] = v;
  for (const auto& [k, v] : c.host_env) own[k] = v;
  own[comm::kEnvParticipantId] = std::to_string(participant_id);
  return own;
}
}  // namespace

std::vector<std::string> child_environment(const Child& c, const Environment& env, int participant_id) {
  const Environment own = own_environment(c, env, participant_id);
  std::vector<std::string> out;
  for (char** e = environ; *e; ++e) {
    const std::string kv = *e;
    if (!own.count(kv.substr(0, kv.find('=')))) out.push_back(kv);
  }
  for (const auto& [k, v] : own) out.push_back(k + "=" + v);
  return out;
}

pid_t start_process(std::vector<std::string> argv, std::vector<std::string> env, const std::string& out_path,
                    int pass_fd) {
  // Everything the child needs is prepared before it starts: until exec it shares the
  // launcher's memory and may only make system calls (no allocation; start_child above).
  std::vector<char*> envp, args;
  for (auto& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);
  for (auto& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  ChildStart start{args.data(), envp.data(), out_path.c_str(), getpid(), pass_fd, {}};
  return start_child(start);
}

void spawn(Child& c, const std::string& run_dir, const Environment& env, int participant_id, Zygote* zygote) {
  const std::string err_path = run_dir + "/logs/" + c.name + ".stderr";
  std::vector<std::string> env_list = child_environment(c, env, participant_id);
  std::vector<std::string> command = {c.binary};
  command.insert(command.end(), c.args.begin(), c.args.end());
  pid_t pid = -1;
  // An agent on this machine is forked from the zygote when there is one (deploy/fleet/zygote_client.hpp);
  // if the zygote is gone, it is started as any other child.
  if (zygote && c.prefix.empty() && zygote->serves(c.binary)) pid = zygote->fork_copy(command, env_list, err_path);
  if (pid <= 0) {
    if (!c.prefix.empty()) command = host_argv(c.prefix, own_environment(c, env, participant_id), c.binary, c.args);
    pid = start_process(std::move(command), std::move(env_list), err_path, -1);
  }
  if (pid < 0) throw std::runtime_error("cannot start " + c.name + " (clone failed)");
  c.pid = pid;
  c.remote_pid = -1;  // known again from this start's NodeReady
  c.participant_id = participant_id;
  c.running = true;
  c.exit_code = -1;
  c.signal = 0;
  ++c.starts;
}

std::optional<Exit> reap_one() {
  int st = 0;
  rusage ru{};
  const pid_t pid = wait4(-1, &st, WNOHANG, &ru);
  if (pid <= 0) return std::nullopt;
  return exit_of(pid, st, ru.ru_maxrss);
}

void signal_all(const std::vector<Child>& kids, int sig) {
  for (const auto& c : kids)
    if (c.running && c.pid > 1) kill(c.pid, sig);  // only what the launcher started
}

void wait_all(const std::vector<Child>& kids, double seconds, const std::function<void()>& reap) {
  auto all_done = [&] {
    return std::none_of(kids.begin(), kids.end(), [](const Child& c) { return c.running; });
  };
  const auto t0 = Clock::now();
  while (!all_done() && since(t0) < seconds) {
    reap();
    std::this_thread::sleep_for(kEndPoll);
  }
}

void stop_process(pid_t pid, double term_s) {
  if (pid <= 1) return;  // never kill(-1, ...) or kill(0, ...): every process, or the launcher's group
  kill(pid, SIGTERM);
  const auto t0 = Clock::now();
  while (waitpid(pid, nullptr, WNOHANG) != pid) {
    if (since(t0) > term_s) {
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
      return;
    }
    std::this_thread::sleep_for(kStopPoll);
  }
}

bool runs_binary(pid_t pid, const std::string& binary) {
  if (pid <= 1) return false;
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/" + std::to_string(pid) + "/exe", ec);
  return !ec && exe == std::filesystem::weakly_canonical(binary, ec);
}

int ParticipantIds::take(int base, int starts) {
  const int id = base + (starts % windows_) * stride_;
  highest_ = std::max(highest_, id);
  return id;
}

bool gate_pending(const std::vector<Child>& kids, const std::vector<std::string>& killed,
                  const std::vector<std::string>& restarted) {
  const auto in = [](const std::vector<std::string>& v, const std::string& n) {
    return std::find(v.begin(), v.end(), n) != v.end();
  };
  for (const auto& c : kids) {
    if (c.awaiting_ready && c.running && in(restarted, c.name)) return true;
    if (c.running && in(killed, c.name)) return true;
  }
  return false;
}

}  // namespace maptr::deploy::fleet
