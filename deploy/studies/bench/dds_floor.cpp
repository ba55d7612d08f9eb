#include "deploy/studies/bench/dds_floor.hpp"

#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <new>
#include <chrono>
#include <functional>
#include <numeric>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "comm/dds/dds.hpp"
#include "comm/dds/process.hpp"
#include "deploy/fleet/config.hpp"
#include "deploy/fleet/discovery.hpp"
#include "deploy/studies/bench/proc_stats.hpp"
#include "idl/maptrPubSubTypes.h"

namespace maptr::deploy {

namespace {

using Clock = std::chrono::steady_clock;
constexpr const char* kTickTopic = "maptr/floor_tick";
constexpr const char* kReplyTopic = "maptr/floor_reply";
/// A round not complete after this long writes its tick again (a best-effort sample was lost).
constexpr auto kResendAfter = std::chrono::milliseconds(200);
constexpr auto kMatchPoll = std::chrono::milliseconds(20);
constexpr double kLeaseS = 10.0;

/// The fleet's transport on one host: user data on shared memory (port queue as the launcher
/// sets it), discovery over UDP through a discovery server of its own.
comm::DdsOptions probe_options(const DdsFloorOptions& o, const std::string& server, bool is_server,
                               int participant_id) {
  comm::DdsOptions d;
  // Explicit ids, as a fleet's (comm/dds/fleet_ids.hpp): Fast DDS's own search for a free id
  // gives up after about a hundred participants on one host.
  d.participant_id = participant_id;
  d.domain = o.domain;
  d.discovery_server = server;
  d.is_server = is_server;
  d.lease_s = kLeaseS;
  d.shm_port_queue = static_cast<uint32_t>(fleet::FleetConfig().shm_port_queue(o.agents > 0 ? o.agents : o.workers));
  return d;
}

/// A worker: waits for its wave's byte on `go`, then answers every tick with one AgentReply from
/// its reader's listener, until the hub closes `go` (EOF).
[[noreturn]] void worker(const DdsFloorOptions& o, const std::string& server, int index, int go) {
  char c;
  if (read(go, &c, 1) != 1) _exit(0);
  {
    comm::Signal signal;
    comm::Direct<msg::PlantTick> ticks(signal);
    comm::Participant p("floor-worker-" + std::to_string(index), probe_options(o, server, false, 2 + index));
    auto* w = p.writer(p.topic<msg::AgentReplyPubSubType>(kReplyTopic), comm::Profile::kStream);
    msg::AgentReply reply;
    reply.side(index % 2 ? msg::SIDE_R : msg::SIDE_L);
    reply.index(static_cast<uint16_t>(index / 2));
    ticks.set_handler([&](const msg::PlantTick& t, const auto&) {
      reply.tick(t.tick());
      w->write(&reply);
    });
    p.reader(p.topic<msg::PlantTickPubSubType>(kTickTopic), comm::Profile::kStream, &ticks);
    while (read(go, &c, 1) > 0) {
    }
    ticks.set_handler({});
  }
  _exit(0);
}

/// The discovery server, a process of its own as in a fleet: a participant that only relays
/// discovery, until `quit` is closed.
[[noreturn]] void discovery_server(const DdsFloorOptions& o, const std::string& server, int quit) {
  {
    comm::Participant p("floor-discovery", probe_options(o, server, true, 0));
    char c;
    while (read(quit, &c, 1) > 0) {
    }
  }
  _exit(0);
}

struct Workers {
  std::vector<pid_t> pids;
  std::vector<int> go;  ///< write ends: the server's, then one per worker (a byte starts it); closing ends each
  ~Workers() {
    for (int fd : go) close(fd);
    for (pid_t p : pids) waitpid(p, nullptr, 0);
  }
  /// Starts workers [from, to) (go[0] is the server's).
  void release(int from, int to) {
    for (int i = from; i < to; ++i)
      if (write(go[static_cast<std::size_t>(i) + 1], "g", 1) != 1) throw std::runtime_error("a worker went away");
  }
};

/// Forks a child of the probe that runs `body` with the read end of its own pipe (the parent
/// keeps the write end in ws.go) and never returns.
void spawn(Workers& ws, const std::function<void(int)>& body) {
  int g[2];
  if (pipe(g) != 0) throw std::runtime_error("pipe() failed");
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork() failed");
  if (pid == 0) {
    for (int fd : ws.go) close(fd);  // the siblings' ends: each child sees only its own EOF
    close(g[1]);
    body(g[0]);
    _exit(0);
  }
  close(g[0]);
  ws.go.push_back(g[1]);
  ws.pids.push_back(pid);
}

/// The discovery server (go[0], started at once) and the workers (waiting for their byte).
void start_workers(Workers& ws, const DdsFloorOptions& o, const std::string& server) {
  spawn(ws, [&](int quit) { discovery_server(o, server, quit); });
  for (int i = 0; i < o.workers; ++i) spawn(ws, [&, i](int go) { worker(o, server, i, go); });
}

/// The tick as the plant sends it to a fleet of `agents`: each side's sequences N/2 long.
msg::PlantTick fleet_sized_tick(int agents) {
  msg::PlantTick t;
  const std::size_t per_side = static_cast<std::size_t>(agents / 2);
  for (auto& s : t.sides()) {
    s.active(std::vector<uint8_t>(per_side, 1));
    s.live(std::vector<uint8_t>(per_side, 1));
    s.wake(std::vector<uint8_t>(per_side, 1));
  }
  t.paused(std::vector<uint8_t>(static_cast<std::size_t>(agents + 3), 0));
  return t;
}

double cpu_us_of(const Workers& ws) {
  double s = read_proc_counters(getpid()).value_or(ProcCounters{}).cpu_s;
  for (pid_t p : ws.pids) s += read_proc_counters(p).value_or(ProcCounters{}).cpu_s;
  return s * 1e6;
}

/// The hub: the tick writer and the reply reader; times the rounds.
class Hub {
 public:
  Hub(const DdsFloorOptions& o, const std::string& server)
      : o_(o), p_("floor-hub", probe_options(o, server, false, 1)), tick_(fleet_sized_tick(o.agents > 0 ? o.agents : o.workers)) {
    w_ = p_.writer(p_.topic<msg::PlantTickPubSubType>(kTickTopic), comm::Profile::kStream, &match_);
    p_.reader(p_.topic<msg::AgentReplyPubSubType>(kReplyTopic), comm::Profile::kStream, &replies_);
  }

  /// Starts the workers in waves of the launcher's size, each once the one before is matched
  /// both ways (as the launcher starts a fleet: all at once, discovery storms); false when a
  /// wave is not matched within `timeout_s` of its start.
  bool matched(Workers& ws, double timeout_s) {
    const int wave = static_cast<int>(fleet::FleetConfig().wave_size);
    for (int from = 0; from < o_.workers; from += wave) {
      const int to = std::min(o_.workers, from + wave);
      ws.release(from, to);
      const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s));
      while (match_.matched() < to || replies_.matched() < to) {
        if (Clock::now() >= end) return false;
        std::this_thread::sleep_for(kMatchPoll);
      }
    }
    return true;
  }
  std::string match_state() const {
    return std::to_string(match_.matched()) + " tick readers and " + std::to_string(replies_.matched()) +
           " reply writers of " + std::to_string(o_.workers);
  }

  /// One round: tick k to every worker, then every worker's answer to it. µs.
  double round(unsigned long long k) {
    std::set<uint16_t> answered;  // by worker (side, index) as one number
    const auto t0 = Clock::now();
    tick_.tick(k);
    w_->write(&tick_);
    auto resend_at = t0 + kResendAfter;
    uint64_t seen = signal_.count();
    while (static_cast<int>(answered.size()) < o_.workers) {
      signal_.wake_at(signal_.arrivals() + static_cast<uint64_t>(o_.workers) - answered.size());
      for (auto& [r, h] : replies_.drain())
        if (r.tick() == k) answered.insert(static_cast<uint16_t>(r.index() * 2 + (r.side() == msg::SIDE_R)));
      if (static_cast<int>(answered.size()) >= o_.workers) break;
      if (Clock::now() >= resend_at) {
        w_->write(&tick_);
        ++resent_;
        resend_at = Clock::now() + kResendAfter;
      }
      seen = signal_.wait_until(seen, resend_at);
    }
    signal_.wake_at(0);
    return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
  }
  long resent() const { return resent_; }

 private:
  const DdsFloorOptions& o_;
  comm::Signal signal_;
  comm::Inbox<msg::AgentReply> replies_{signal_, comm::Wake::kCounted};
  comm::MatchCounter match_;
  comm::Participant p_;
  eprosima::fastdds::dds::DataWriter* w_ = nullptr;
  msg::PlantTick tick_;
  long resent_ = 0;
};

}  // namespace

namespace {

/// The probe itself, in a process of its own (measure_dds_floor's child).
DdsFloorResult probe(const DdsFloorOptions& o) {
  DdsFloorResult r;
  r.workers = o.workers;
  try {
    const std::string server = "127.0.0.1:" + std::to_string(fleet::free_udp_port());
    const auto t0 = Clock::now();
    Workers ws;
    start_workers(ws, o, server);  // before this process has any DDS entity
    if (o.hub_priority > 0) comm::make_thread_realtime(o.hub_priority);
    Hub hub(o, server);
    if (!hub.matched(ws, o.match_timeout_s)) {
      r.problem = "matched " + hub.match_state() + " within " + std::to_string(o.match_timeout_s) + " s";
      return r;
    }
    r.match_s = std::chrono::duration<double>(Clock::now() - t0).count();
    unsigned long long k = 0;
    r.first_round_us = hub.round(k++);  // the first write opens every worker's port
    for (long i = 1; i < o.warmup; ++i) hub.round(k++);
    const long resent0 = hub.resent();
    const double cpu0 = cpu_us_of(ws);
    std::vector<double> t(static_cast<std::size_t>(o.rounds));
    for (auto& x : t) x = hub.round(k++);
    r.cpu_us_per_round = (cpu_us_of(ws) - cpu0) / static_cast<double>(o.rounds);
    r.resent = hub.resent() - resent0;
    r.rounds = o.rounds;
    r.mean_us = std::accumulate(t.begin(), t.end(), 0.0) / static_cast<double>(t.size());
    std::sort(t.begin(), t.end());
    r.median_us = t[t.size() / 2];
    r.p99_us = t[static_cast<std::size_t>(0.99 * static_cast<double>(t.size() - 1))];
    r.measured = true;
  } catch (const std::exception& e) {
    r.problem = e.what();
  }
  return r;
}

}  // namespace

DdsFloorResult measure_dds_floor(const DdsFloorOptions& o) {
  DdsFloorResult r;
  r.workers = o.workers;
  if (o.workers < 1 || o.rounds < 1) {
    r.problem = "needs at least one worker and one round";
    return r;
  }
  // Fast DDS never starts in the calling process: a process that forks fleets afterwards (the
  // benches) must not hold its threads and locks. The child writes its figures into a page both
  // share (a plain struct: no file, no format).
  struct Shared {
    bool done = false, measured = false;
    DdsFloorFigures figures;
    char problem[512] = {};
  };
  void* page = mmap(nullptr, sizeof(Shared), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (page == MAP_FAILED) {
    r.problem = "mmap() failed";
    return r;
  }
  auto* shared = new (page) Shared;
  const pid_t pid = fork();
  if (pid == 0) {
    const DdsFloorResult m = probe(o);
    shared->figures = m;
    shared->measured = m.measured;
    m.problem.copy(shared->problem, sizeof(shared->problem) - 1);
    shared->done = true;
    _exit(0);  // no static destructors: the workers are gone, the participants deleted
  }
  int status = 0;
  if (pid > 0) waitpid(pid, &status, 0);
  const Shared s = *shared;
  munmap(page, sizeof(Shared));
  if (pid < 0 || !s.done) {
    r.problem = pid < 0 ? "fork() failed" : "the probe process ended without a result (wait status " + std::to_string(status) + ")";
    return r;
  }
  static_cast<DdsFloorFigures&>(r) = s.figures;
  r.measured = s.measured;
  r.problem = s.problem;
  return r;
}

}  // namespace maptr::deploy
