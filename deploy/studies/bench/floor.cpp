#include "deploy/studies/bench/floor.hpp"

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "deploy/studies/bench/proc_stats.hpp"

namespace maptr::deploy {

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kMessageBytes = 4;

/// Context switches (voluntary + involuntary) of a single-threaded process so far.
long context_switches(pid_t pid) { return static_cast<long>(read_main_thread_ctx_switches(pid).value_or(0)); }

/// User + system CPU of a process so far, µs (clock-tick resolution).
double cpu_us(pid_t pid) {
  const auto c = read_proc_counters(pid);
  return c ? c->cpu_s * 1e6 : 0.0;
}

constexpr std::size_t kCacheLine = 64;
constexpr std::size_t kKiB = 1024;

[[noreturn]] void worker(int in, int out, int touch_kb) {
  char buf[kMessageBytes];
  // The working set, faulted in before the first round.
  std::vector<unsigned char> mem(static_cast<std::size_t>(touch_kb) * kKiB, 1);
  while (read(in, buf, sizeof(buf)) == kMessageBytes) {
    for (std::size_t i = 0; i < mem.size(); i += kCacheLine)
      mem[i] = static_cast<unsigned char>(mem[i] + buf[0]);
    if (write(out, buf, sizeof(buf)) != kMessageBytes) break;
  }
  volatile unsigned char used = mem.empty() ? 0 : mem[0];  // the writes are read: the compiler keeps them
  (void)used;
  _exit(0);
}

struct Workers {
  std::vector<int> to;  ///< write ends, one per worker
  int from = -1;        ///< read end of the shared answer pipe
  std::vector<pid_t> pids;
  ~Workers() {
    for (int fd : to) close(fd);  // EOF: every worker ends
    if (from >= 0) close(from);
    for (pid_t p : pids) waitpid(p, nullptr, 0);
  }
};

void start(Workers& w, int n, int touch_kb) {
  int answer[2];
  if (pipe(answer) != 0) throw std::runtime_error("floor probe: pipe() failed");
  w.from = answer[0];
  for (int i = 0; i < n; ++i) {
    int p[2];
    if (pipe(p) != 0) throw std::runtime_error("floor probe: pipe() failed");
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("floor probe: fork() failed");
    if (pid == 0) {
      for (int fd : w.to) close(fd);
      close(p[1]);
      close(answer[0]);
      worker(p[0], answer[1], touch_kb);
    }
    close(p[0]);
    w.to.push_back(p[1]);
    w.pids.push_back(pid);
  }
  close(answer[1]);
}

/// One round: a message to every worker, then every answer. Returns its wall time, µs.
double round_trip(const Workers& w) {
  const char msg[kMessageBytes] = {'t', 'i', 'c', 'k'};
  char buf[4096];
  const auto t0 = Clock::now();
  for (int fd : w.to)
    if (write(fd, msg, sizeof(msg)) != kMessageBytes) throw std::runtime_error("floor probe: write failed");
  std::size_t want = w.to.size() * kMessageBytes, got = 0;
  while (got < want) {
    const ssize_t n = read(w.from, buf, std::min(sizeof(buf), want - got));
    if (n <= 0) throw std::runtime_error("floor probe: a worker went away");
    got += static_cast<std::size_t>(n);
  }
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
}

/// Context switches and CPU of the hub and every worker so far.
std::pair<long, double> usage(const Workers& w) {
  long cs = context_switches(getpid());
  double cpu = cpu_us(getpid());
  for (pid_t p : w.pids) {
    cs += context_switches(p);
    cpu += cpu_us(p);
  }
  return {cs, cpu};
}

}  // namespace

FloorResult measure_floor(int workers, long rounds, long warmup, int touch_kb) {
  if (workers < 1 || rounds < 1)
    throw std::invalid_argument("floor probe: needs at least one worker and one round");
  if (touch_kb < 0) throw std::invalid_argument("floor probe: the working set cannot be negative");
  Workers w;
  start(w, workers, touch_kb);
  for (long r = 0; r < warmup; ++r) round_trip(w);
  const auto before = usage(w);
  std::vector<double> t(static_cast<std::size_t>(rounds));
  for (auto& x : t) x = round_trip(w);
  const auto after = usage(w);
  std::sort(t.begin(), t.end());
  FloorResult f;
  f.workers = workers;
  f.touch_kb = touch_kb;
  f.rounds = rounds;
  f.median_us = t[t.size() / 2];
  f.p99_us = t[static_cast<std::size_t>(0.99 * static_cast<double>(t.size() - 1))];
  f.ctx_switches_per_round = static_cast<double>(after.first - before.first) / static_cast<double>(rounds);
  f.cpu_us_per_round = (after.second - before.second) / static_cast<double>(rounds);
  return f;
}

}  // namespace maptr::deploy
