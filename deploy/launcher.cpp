#include "deploy/launcher.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "comm/dds.hpp"
#include "comm/shm_files.hpp"
#include "deploy/faults.hpp"
#include "idl/maptrPubSubTypes.h"

namespace maptr::deploy {

namespace {

using Clock = std::chrono::steady_clock;
std::atomic<bool> g_interrupted{false};
void on_signal(int) { g_interrupted.store(true); }

struct Child {
  std::string name, binary;
  std::vector<std::string> args;
  uint8_t kind = 0, side = 0;
  uint16_t index = 0;
  pid_t pid = -1;
  bool running = false;
  bool external = false;  ///< started by the user, not by the launcher
  int exit_code = -1, signal = 0;
  long max_rss_kB = 0;
  int starts = 0;
  int base_id = 0;  ///< DDS participant id of its first start
  bool awaiting_ready = false;  ///< restarted: MEMBER_STARTED goes out once it reports ready
};

double wall_ms_now() {
  return std::chrono::duration<double, std::milli>(std::chrono::system_clock::now().time_since_epoch()).count();
}

int free_udp_port() {
  int fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  socklen_t len = sizeof(a);
  if (fd < 0 || bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0 ||
      getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
    if (fd >= 0) close(fd);
    throw std::runtime_error("cannot find a free UDP port on 127.0.0.1");
  }
  close(fd);
  return ntohs(a.sin_port);
}

std::string sha256_of(const std::string& path) {
  std::string cmd = "sha256sum '" + path + "'";
  FILE* f = popen(cmd.c_str(), "r");
  if (!f) return "";
  char buf[128] = {0};
  std::string out;
  if (fgets(buf, sizeof(buf), f)) out = buf;
  pclose(f);
  return out.substr(0, out.find(' '));
}

/// True once some process has bound UDP port `port` on 127.0.0.1 (the discovery server is up).
bool udp_port_bound(int port) {
  int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return false;
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<uint16_t>(port));
  const bool taken = bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0 && errno == EADDRINUSE;
  close(fd);
  return taken;
}

void spawn(Child& c, const std::string& run_dir, const std::map<std::string, std::string>& env, int participant_id) {
  // Everything the child needs is prepared before fork(): between fork and exec the child of
  // a multi-threaded process may only make async-signal-safe calls (no allocation).
  const std::string err_path = run_dir + "/logs/" + c.name + ".stderr";
  std::vector<std::string> env_store;
  for (char** e = environ; *e; ++e) {
    const std::string kv = *e;
    if (!env.count(kv.substr(0, kv.find('=')))) env_store.push_back(kv);
  }
  for (const auto& [k, v] : env) env_store.push_back(k + "=" + v);
  env_store.push_back("MAPTR_PARTICIPANT_ID=" + std::to_string(participant_id));
  std::vector<char*> envp, argv;
  for (auto& e : env_store) envp.push_back(e.data());
  envp.push_back(nullptr);
  argv.push_back(const_cast<char*>(c.binary.c_str()));
  for (auto& a : c.args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed for " + c.name);
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(1);
    setpgid(0, 0);  // a Ctrl-C in the terminal reaches the launcher only; it ends the children
    const int fd = open(err_path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    execve(argv[0], argv.data(), envp.data());
    _exit(127);
  }
  c.pid = pid;
  c.running = true;
  c.exit_code = -1;
  c.signal = 0;
  ++c.starts;
}

/// Level-2 figures of a run from the groups' level2-<side>.csv: decisions, Ipopt solve time
/// (median, p95, max) and, where the oracle ran on a solved problem, how often Ipopt's integer
/// differed from the exhaustive search's.
nlohmann::json level2_stats(const std::string& run_dir) {
  nlohmann::json out = nlohmann::json::object();
  for (const char* side : {"L", "R"}) {
    std::ifstream in(run_dir + "/level2-" + side + ".csv");
    if (!in) continue;
    std::string line;
    std::getline(in, line);
    std::vector<double> ms;
    int checked = 0, differs = 0, infeasible = 0;
    while (std::getline(in, line)) {
      std::vector<double> f;
      std::stringstream ss(line);
      for (std::string c; std::getline(ss, c, ',');) f.push_back(std::atof(c.c_str()));
      if (f.size() < 9) continue;
      ms.push_back(f[8]);
      if (static_cast<int>(f[3]) == msg::L2_INFEASIBLE) ++infeasible;
      if (static_cast<int>(f[3]) == msg::L2_OK && f[6] >= 0) {
        ++checked;
        if (static_cast<int>(f[5]) != static_cast<int>(f[6])) ++differs;
      }
    }
    nlohmann::json s = {{"decisions", ms.size()}, {"infeasible", infeasible},
                        {"oracle_checked", checked}, {"oracle_differs", differs}};
    if (!ms.empty()) {
      std::sort(ms.begin(), ms.end());
      auto q = [&](double p) { return ms[std::min(ms.size() - 1, static_cast<std::size_t>(p * (ms.size() - 1) + 0.5))]; };
      s["solve_ms_median"] = q(0.5);
      s["solve_ms_p95"] = q(0.95);
      s["solve_ms_max"] = ms.back();
    }
    out[side] = s;
  }
  return out;
}

}  // namespace

namespace {
/// DDS participants of a fleet: discovery server, launcher, plant, central, 2 groups, agents.
/// Wall time a fault gate waits for a restarted process to report ready, s (plus 0.5 s per agent).
constexpr double kRestartReadyS = 30.0;

int fleet_participants(int agents) { return 2 + 4 + agents; }
}  // namespace

std::string domain_problem(int domain, int agents) {
  const int last_id = fleet_participants(agents) - 1;
  if (domain >= 0 && last_id <= comm::rtps_max_participant_id(domain)) return "";
  int highest = domain;
  while (highest > 0 && last_id > comm::rtps_max_participant_id(highest)) --highest;
  return "--domain " + std::to_string(domain) + ": a fleet of " + std::to_string(agents) + " agents has " +
         std::to_string(last_id + 1) + " DDS participants, whose ports would go up to " +
         std::to_string(*comm::rtps_ports(domain, last_id).rbegin()) + ", above 65535; use a domain from 0 to " +
         std::to_string(highest);
}

nlohmann::json launch(const LaunchOptions& o, spdlog::logger& log) {
  const config::Scenario& sc = o.scenario;
  namespace fs = std::filesystem;
  fs::create_directories(o.run_dir + "/logs");
  const std::string cfg = o.run_dir + "/scenario.yaml";
  std::ofstream(cfg) << config::to_yaml(sc);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  // Shared-memory ports that earlier fleets left behind on this machine (same domain, same
  // port numbers) can keep this fleet from discovering itself.
  if (const int stale = comm::clean_stale_shm(); stale > 0)
    log.info("removed {} unused Fast DDS shared-memory ports left in /dev/shm by earlier runs", stale);

  // A discovery server of the fleet's own (participant id 0), started first and ended last:
  // clients find only what they need through it. The launcher is a client too (id 1).
  comm::DdsOptions dds;
  dds.domain = o.domain;
  const int ds_port = free_udp_port();
  dds.discovery_server = "127.0.0.1:" + std::to_string(ds_port);
  dds.participant_id = 1;
  // Leases grow with the fleet: on two cores a large fleet starves participants for seconds.
  dds.lease_s = std::max(2.0, 0.05 * sc.robot.agents);
  const std::string transport =
      o.transport != "auto" ? o.transport : (sc.robot.agents <= 64 ? std::string("shm") : std::string("udp"));
  dds.shm = transport == "shm";
  // The fleet id makes every participant's GUID prefix say which process of this fleet it is
  // (comm/fleet_ids.hpp): followers take ticks only from the plant's writer.
  dds.fleet_id = std::random_device{}() | 1u;
  const std::map<std::string, std::string> env = {
      {"MAPTR_FLEET_ID", std::to_string(dds.fleet_id)},
      {"MAPTR_TRANSPORT", transport},
      {"MAPTR_DOMAIN", std::to_string(o.domain)},
      {"MAPTR_DISCOVERY_SERVER", dds.discovery_server},
      {"MAPTR_LEASE_S", std::to_string(dds.lease_s)}};
  const std::vector<std::string> common = {"--config", cfg, "--run-dir", o.run_dir};

  // Participant ids: 0 the discovery server, 1 the launcher, then the fleet (plant, central,
  // groups, agents). A fresh id (and so fresh ports) at every start: a restarted process never
  // reuses the shared-memory ports its killed predecessor left behind.
  const int id_stride = fleet_participants(sc.robot.agents);
  // Fast DDS derives each participant's ports from its id (comm::rtps_ports). Restarts cycle
  // through as many id windows as stay below port 65536; the oldest window's ports belong to
  // processes that are long gone.
  const int id_windows = (comm::rtps_max_participant_id(o.domain) + 1) / id_stride;
  if (id_windows < 1) throw std::runtime_error(domain_problem(o.domain, sc.robot.agents));
  auto participant_id = [&](int base, int starts) { return base + (starts % id_windows) * id_stride; };
  Child ds;
  ds.name = "discovery";
  ds.binary = o.bin_dir + "/maptr_discovery";
  ds.args = {"--address", dds.discovery_server, "--domain", std::to_string(o.domain)};
  if (!fs::exists(ds.binary)) throw std::runtime_error("missing process binary " + ds.binary);
  int ds_restarts = 0;
  int max_participant_id = 1;  ///< highest id given to a process of this fleet (ports to clean up)
  std::optional<Clock::time_point> ds_restart_at;
  // Starts the server (again) and waits until it listens.
  auto start_discovery = [&]() -> bool {
    const int id = participant_id(0, ds_restarts);  // fresh ports after a restart
    max_participant_id = std::max(max_participant_id, id);
    spawn(ds, o.run_dir, env, id);
    const auto t0 = Clock::now();
    while (std::chrono::duration<double>(Clock::now() - t0).count() < 10.0) {
      if (udp_port_bound(ds_port)) return true;
      int st = 0;
      if (waitpid(ds.pid, &st, WNOHANG) == ds.pid) {
        ds.running = false;
        return false;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  };
  if (!start_discovery()) {
    if (ds.running) kill(ds.pid, SIGKILL), waitpid(ds.pid, nullptr, 0);
    throw std::runtime_error("the discovery server did not start on " + dds.discovery_server + " (see " + o.run_dir +
                             "/logs/discovery.stderr)");
  }

  comm::Signal signal;
  comm::Inbox<msg::NodeReady> ready(signal);
  comm::Inbox<msg::PlantTick> ticks(signal);
  comm::Inbox<msg::FaultGate> gates(signal);
  auto participant = std::make_unique<comm::Participant>("launcher", dds);
  auto& p = *participant;
  p.reader(p.topic<msg::NodeReadyPubSubType>(comm::topic::kReady), comm::Profile::kLatched, &ready);
  p.reader(p.topic<msg::PlantTickPubSubType>(comm::topic::kTick), comm::Profile::kStream, &ticks);
  auto* w_member = p.writer(p.topic<msg::MembershipEventPubSubType>(comm::topic::kMembership), comm::Profile::kLatched);
  auto* w_control = p.writer(p.topic<msg::ControlPubSubType>(comm::topic::kControl), comm::Profile::kLatched);
  p.reader(p.topic<msg::FaultGatePubSubType>(comm::topic::kGate), comm::Profile::kLatched, &gates);

  std::vector<Child> kids;
  auto add = [&](const std::string& name, const std::string& bin, std::vector<std::string> extra, uint8_t kind,
                 uint8_t side, uint16_t index) {
    Child c;
    c.name = name;
    c.binary = o.bin_dir + "/" + bin;
    c.args = common;
    c.args.insert(c.args.end(), extra.begin(), extra.end());
    c.kind = kind;
    c.side = side;
    c.index = index;
    kids.push_back(c);
  };
  add("plant", "maptr_plant", {}, msg::NODE_PLANT, 0, 0);
  add("central", "maptr_central", {}, msg::NODE_CENTRAL, 0, 0);
  add("group-L", "maptr_group", {"--side", "L"}, msg::NODE_GROUP, 0, 0);
  add("group-R", "maptr_group", {"--side", "R"}, msg::NODE_GROUP, 1, 0);
  for (int s = 0; s < 2; ++s)
    for (int j = 0; j < sc.robot.per_side(); ++j) {
      const std::string n = config::agent_name(s, j);
      add(n, "maptr_agent", {"--id", n}, msg::NODE_AGENT, static_cast<uint8_t>(s), static_cast<uint16_t>(j));
    }
  for (std::size_t i = 0; i < kids.size(); ++i) kids[i].base_id = static_cast<int>(i) + 2;
  auto spawn_kid = [&](Child& c) {
    const int id = participant_id(c.base_id, c.starts);
    max_participant_id = std::max(max_participant_id, id);
    spawn(c, o.run_dir, env, id);
  };
  for (const auto& c : kids)
    if (!fs::exists(c.binary)) throw std::runtime_error("missing process binary " + c.binary);

  const auto t_launch = Clock::now();
  auto since = [&](Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  for (auto& c : kids)
    if (std::find(o.external.begin(), o.external.end(), c.name) != o.external.end()) c.external = true;
  // The fleet's coordinates, for tools and for processes started by hand (rewritten as waves start).
  auto write_fleet = [&] {
    nlohmann::json fleet = {{"launcher_pid", getpid()},
                            {"domain", o.domain},
                            {"discovery_server", dds.discovery_server},
                            {"discovery_server_pid", ds.pid},
                            {"lease_s", dds.lease_s},
                            {"fleet_id", dds.fleet_id},
                            {"config", cfg},
                            {"run_dir", o.run_dir},
                            {"bin_dir", o.bin_dir}};
    for (const auto& c : kids)
      fleet["processes"].push_back(
          {{"name", c.name}, {"pid", c.pid}, {"external", c.external}, {"participant_id", c.base_id}});
    std::ofstream(o.run_dir + "/fleet.json.tmp") << fleet.dump(2) << "\n";
    fs::rename(o.run_dir + "/fleet.json.tmp", o.run_dir + "/fleet.json");  // readers never see half a file
  };
  // Staggered launch: the controllers and a first wave of agents, then one wave of agents at a
  // time once the previous wave has matched the plant (or after 20 s): a herd of hundreds of
  // participants starting at once starves the discovery server on two cores.
  constexpr std::size_t kWave = 32;
  std::size_t spawned = 0;
  auto wave_started = Clock::now();
  auto spawn_wave = [&] {
    const std::size_t end = std::min(kids.size(), (spawned == 0 ? 4 : spawned) + kWave);
    for (; spawned < end; ++spawned)
      if (!kids[spawned].external) spawn_kid(kids[spawned]);
    wave_started = Clock::now();
    write_fleet();
  };
  spawn_wave();
  for (const auto& c : kids)
    if (c.external) {
      std::string cmd;
      for (const auto& [k, v] : env) cmd += k + "=" + v + " ";
      cmd += "MAPTR_PARTICIPANT_ID=" + std::to_string(c.base_id) + " " + c.binary;
      for (const auto& a : c.args) cmd += " " + a;
      std::fprintf(stderr, "maptr: waiting for %s; start it with:\n  %s\n", c.name.c_str(), cmd.c_str());
      log.info("external {}: {}", c.name, cmd);
    }
  // Control FIFO: `maptr kill NAME` / `maptr restart NAME` from another terminal.
  const std::string fifo = o.run_dir + "/control";
  ::unlink(fifo.c_str());
  int control_fd = -1;
  if (mkfifo(fifo.c_str(), 0600) == 0) control_fd = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  std::string control_buf;
  log.info("launching {} processes in waves (discovery server {})", kids.size(), dds.discovery_server);
  if (o.progress)
    std::fprintf(stderr, "maptr: launched %zu processes (%d agents, 2 groups, central, plant)\n", kids.size(),
                 sc.robot.agents);

  nlohmann::json summary;
  std::string status = "ok";
  uint64_t member_seq = 0;
  auto by_pid = [&](pid_t pid) -> Child* {
    for (auto& c : kids)
      if (c.pid == pid && c.running) return &c;
    return nullptr;
  };
  bool plant_done = false;
  auto publish_member = [&](const Child& c, uint8_t kind) {
    msg::MembershipEvent e;
    e.seq(++member_seq);
    e.name(c.name);
    e.node_kind(c.kind);
    e.side(c.side);
    e.index(c.index);
    e.kind(kind);
    e.wall_s(since(t_launch));
    w_member->write(&e);
  };
  // Reaps dead children; publishes deaths the fleet did not expect.
  auto reap = [&](bool expected) {
    if (ds_restart_at && Clock::now() >= *ds_restart_at && !expected) {
      ds_restart_at.reset();
      if (start_discovery())
        log.info("the discovery server runs again (pid {})", ds.pid);
      else
        log.error("the discovery server did not start again");
    }
    int st = 0;
    rusage ru{};
    pid_t pid;
    while ((pid = wait4(-1, &st, WNOHANG, &ru)) > 0) {
      if (pid == ds.pid && ds.running) {
        ds.running = false;
        if (!expected) {
          // Established matches survive; the restarted server lets the clients re-register.
          log.warn("the discovery server (pid {}) died: exit {} signal {}; starting it again", pid,
                   WIFEXITED(st) ? WEXITSTATUS(st) : -1, WIFSIGNALED(st) ? WTERMSIG(st) : 0);
          ++ds_restarts;
          // Restart only once every client's lease on the dead server has expired: a client that
          // still counts the old server as alive would ignore the new one (its sequence numbers
          // start again from 1); one that dropped it registers anew.
          ds_restart_at = Clock::now() + std::chrono::milliseconds(static_cast<long>(1500 * dds.lease_s));
        }
        continue;
      }
      Child* c = by_pid(pid);
      if (!c) continue;
      c->running = false;
      c->exit_code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
      c->signal = WIFSIGNALED(st) ? WTERMSIG(st) : 0;
      c->max_rss_kB = std::max(c->max_rss_kB, ru.ru_maxrss);
      if (c->name == "plant") plant_done = true;
      // A clean exit is a process that saw the plant's last tick; anything else is a failure.
      const bool clean = c->exit_code == 0 && c->signal == 0;
      if (!expected && !clean && c->name != "plant") {
        publish_member(*c, msg::MEMBER_DIED);
        log.warn("{} (pid {}) died: exit {} signal {}", c->name, pid, c->exit_code, c->signal);
      }
    }
  };

  // 1. Discovery: wait until every process says it matched what it needs.
  std::set<std::string> ready_names;
  const double discovery_timeout = 30.0 + 0.5 * sc.robot.agents;
  uint64_t seen = signal.count();
  while (ready_names.size() < kids.size()) {
    seen = signal.wait_until(seen, Clock::now() + std::chrono::milliseconds(50));
    for (auto& [r, h] : ready.drain())
      if (r.ready()) {
        ready_names.insert(r.name());
        for (auto& c : kids)
          if (c.external && c.name == r.name()) c.pid = static_cast<pid_t>(r.pid());
      }
    reap(false);
    if (spawned < kids.size()) {
      bool wave_ready = true;
      for (std::size_t i = 4; i < spawned; ++i)
        if (!kids[i].external && !ready_names.count(kids[i].name)) wave_ready = false;
      if (wave_ready || since(wave_started) > 20.0) {
        spawn_wave();
        log.info("launched agents up to {} of {}", spawned - 4, kids.size() - 4);
      }
    }
    bool early_death = false;
    for (std::size_t i = 0; i < spawned; ++i)
      if (!kids[i].running && !kids[i].external) early_death = true;
    if (early_death || g_interrupted.load() || since(t_launch) > discovery_timeout) {
      std::string missing;
      for (auto& c : kids)
        if (!ready_names.count(c.name)) missing += (missing.empty() ? "" : " ") + c.name;
      status = g_interrupted.load() ? "aborted: interrupted during discovery"
               : early_death        ? "aborted: a process died during discovery (see logs/)"
                                    : "aborted: discovery timed out; not ready: " + missing;
      break;
    }
  }
  const double discovery_s = since(t_launch);
  if (status == "ok") {
    log.info("all {} processes matched after {:.2f} s", kids.size(), discovery_s);
    if (o.progress) std::fprintf(stderr, "maptr: all %zu processes matched in %.2f s; starting\n", kids.size(), discovery_s);
    msg::Control c;
    c.command(msg::CONTROL_START);
    c.seq(1);
    w_control->write(&c);
  }

  // 2. Run: progress, faults, deaths. Scheduled faults act at the plant's fault gates (the
  // first tick at or after their time, held until they are applied), so that they hit the same
  // tick in every run; commands from the control FIFO act at once.
  std::vector<config::FaultSpec> faults = sc.faults;
  std::stable_sort(faults.begin(), faults.end(), [](auto& a, auto& b) { return a.at_s < b.at_s; });
  std::size_t next_fault = 0;
  nlohmann::json failures = nlohmann::json::array();
  const auto t_run = Clock::now();
  auto last_print = Clock::now();
  double sim_t = 0.0, v = 0.0, energy = 0.0;
  int act_L = 0, act_R = 0;
  uint64_t control_seq = 1;
  // Restarted processes report ready: the plant may wait for them from now on.
  auto announce_restarted = [&] {
    for (auto& [r, h] : ready.drain())
      for (auto& c : kids)
        if (c.awaiting_ready && r.ready() && static_cast<pid_t>(r.pid()) == c.pid) {
          c.awaiting_ready = false;
          publish_member(c, msg::MEMBER_STARTED);
          log.info("{} (pid {}) restarted and ready", c.name, c.pid);
        }
  };
  auto apply_fault = [&](const config::FaultSpec& f, double at_s) {
    auto it = std::find_if(kids.begin(), kids.end(), [&](const Child& c) { return c.name == f.target; });
    nlohmann::json rec = {{"target", f.target}, {"action", f.action}, {"at_s", at_s}, {"wall_ms", wall_ms_now()}};
    if (f.target == "discovery") {
      // The launcher restarts a dead discovery server by itself (see reap).
      if (f.action == "kill" && ds.running) {
        kill(ds.pid, SIGKILL);
        log.warn("fault: killed the discovery server (pid {}) at t={:.2f} s", ds.pid, at_s);
      } else {
        rec["skipped"] = "the discovery server is restarted by the launcher when it dies";
      }
    } else if (it != kids.end() && it->external) {
      rec["skipped"] = "an external process is not the launcher's to kill or start";
    } else if (it != kids.end() && f.action == "kill" && it->running) {
      kill(it->pid, SIGKILL);
      log.warn("fault: killed {} (pid {}) at t={:.2f} s", it->name, it->pid, at_s);
    } else if (it != kids.end() && f.action == "restart" && !it->running) {
      spawn_kid(*it);
      it->awaiting_ready = true;
      log.warn("fault: restarted {} (pid {}) at t={:.2f} s", it->name, it->pid, at_s);
    } else {
      rec["skipped"] = "target not in a state for this action";
    }
    failures.push_back(rec);
  };
  // A fault gate: apply every scheduled fault due at its time, wait until each killed process is
  // reaped (its death published) and each restarted one is ready, then let the plant go on.
  auto open_gate = [&](const msg::FaultGate& g) {
    std::vector<std::string> killed;
    while (next_fault < faults.size() && g.t() >= faults[next_fault].at_s) {
      const auto f = faults[next_fault++];
      if (f.action == "kill") killed.push_back(f.target);
      apply_fault(f, g.t());
    }
    const auto t0 = Clock::now();
    const double limit = kRestartReadyS + 0.5 * sc.robot.agents;
    for (;;) {
      reap(false);
      announce_restarted();
      bool pending = false;
      for (const auto& c : kids) {
        pending |= c.awaiting_ready && c.running;
        pending |= c.running && std::find(killed.begin(), killed.end(), c.name) != killed.end();
      }
      if (!pending || g_interrupted.load() || plant_done) break;
      if (since(t0) > limit) {
        log.error("fault gate at t={:.2f} s: a killed process did not end or a restarted one did not report ready "
                  "within {:.0f} s; the plant goes on",
                  g.t(), limit);
        break;
      }
      seen = signal.wait_until(seen, Clock::now() + std::chrono::milliseconds(10));
    }
    msg::Control c;
    c.command(msg::CONTROL_GATE_OPEN);
    c.seq(++control_seq);
    c.tick(g.tick());
    c.member_seq(member_seq);
    w_control->write(&c);
  };
  while (status == "ok" && !plant_done) {
    seen = signal.wait_until(seen, Clock::now() + std::chrono::milliseconds(20));
    for (auto& [t, h] : ticks.drain()) {
      sim_t = t.t();
      v = t.v_x();
      energy = t.energy_J();
      act_L = t.n_active_L();
      act_R = t.n_active_R();
    }
    // Commands from `maptr kill|restart NAME` join the schedule at the current time.
    if (control_fd >= 0) {
      char buf[256];
      ssize_t n;
      while ((n = ::read(control_fd, buf, sizeof(buf))) > 0) control_buf.append(buf, static_cast<std::size_t>(n));
      for (std::size_t nl; (nl = control_buf.find('\n')) != std::string::npos;) {
        std::istringstream line(control_buf.substr(0, nl));
        control_buf.erase(0, nl + 1);
        std::string action, target;
        line >> action >> target;
        if (action == "kill" || action == "restart") {
          log.info("command: {} {}", action, target);
          apply_fault(config::FaultSpec{target, action, sim_t}, sim_t);
        } else {
          log.warn("ignored control command '{}'", action + " " + target);
        }
      }
    }
    for (auto& [g, h] : gates.drain()) {
      sim_t = std::max(sim_t, g.t());
      open_gate(g);
    }
    announce_restarted();
    reap(false);
    if (g_interrupted.load()) status = "aborted: interrupted";
    if (o.progress && since(last_print) >= 1.0) {
      last_print = Clock::now();
      const double rtf = sim_t / std::max(1e-9, since(t_run));
      std::fprintf(stderr, "maptr: t=%7.1f/%.0f s  RTF %6.1f  v=%6.3f m/s  active L%d R%d  E=%.1f kJ\n", sim_t,
                   sc.duration_s, rtf, v, act_L, act_R, energy / 1000.0);
    }
  }
  const double run_wall_s = since(t_run);
  for (; next_fault < faults.size(); ++next_fault)
    failures.push_back({{"target", faults[next_fault].target},
                        {"action", faults[next_fault].action},
                        {"at_s", faults[next_fault].at_s},
                        {"skipped", "scheduled after the end of the run"}});

  // 3. End every process: the plant's last tick tells them; then SIGTERM, then SIGKILL.
  auto all_done = [&] {
    for (auto& c : kids)
      if (c.running) return false;
    return true;
  };
  auto wait_all = [&](double seconds) {
    const auto t0 = Clock::now();
    while (!all_done() && since(t0) < seconds) {
      reap(true);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  };
  wait_all(status == "ok" ? 10.0 : 0.5);
  for (auto& c : kids)
    if (c.running) kill(c.pid, SIGTERM);
  wait_all(3.0);
  for (auto& c : kids)
    if (c.running) kill(c.pid, SIGKILL);
  wait_all(5.0);
  if (control_fd >= 0) ::close(control_fd);
  ::unlink(fifo.c_str());
  participant.reset();
  // The discovery server goes last.
  if (ds.running) {
    kill(ds.pid, SIGTERM);
    const auto t0 = Clock::now();
    while (waitpid(ds.pid, nullptr, WNOHANG) != ds.pid) {
      if (since(t0) > 3.0) {
        kill(ds.pid, SIGKILL);
        waitpid(ds.pid, nullptr, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ds.running = false;
  }
  // Every process of the fleet has ended: its ports go now, whatever their age, with what
  // older runs left.
  {
    std::set<int> own = comm::rtps_ports(o.domain, max_participant_id);
    own.insert(ds_port);
    if (const int removed = comm::clean_stale_shm(own); removed > 0)
      log.info("removed {} unused Fast DDS shared-memory ports from /dev/shm (this fleet's and older ones)", removed);
  }

  // 4. Summary.
  nlohmann::json plant;
  {
    std::ifstream in(o.run_dir + "/plant.json");
    if (in) try {
        in >> plant;
      } catch (...) {
      }
  }
  if (!plant.is_object()) plant = nlohmann::json::object();
  const Child& pc = kids.front();
  if (status == "ok") {
    if (plant.empty())
      status = "aborted: the plant ended without results (exit " + std::to_string(pc.exit_code) + ", signal " +
               std::to_string(pc.signal) + ")";
    else
      status = plant.value("status", "unknown");
  }
  summary["scenario"] = sc.name;
  // A scenario of the project is recorded by its path in the project (results are committed
  // and must not carry the paths of the machine that made them).
  {
    const std::string root = std::string(MAPTR_SOURCE_DIR) + "/";
    summary["scenario_file"] = sc.source.rfind(root, 0) == 0 ? sc.source.substr(root.size()) : sc.source;
  }
  summary["agents"] = sc.robot.agents;
  summary["mode"] = sc.mode;
  summary["motor"] = sc.robot.motor.type;
  summary["gross_mass_kg"] = sc.robot.gross_mass_kg;
  summary["tick_hz"] = sc.tick_hz;
  summary["sim_time_s"] = plant.value("sim_time_s", sim_t);
  summary["wall_time_s"] = run_wall_s;
  summary["ticks"] = plant.value("ticks", 0);
  summary["real_time_factor"] = plant.value("sim_time_s", sim_t) / std::max(1e-9, run_wall_s);
  summary["distance_m"] = plant.value("distance_m", 0.0);
  summary["energy_J"] = plant.value("energy_J", energy);
  summary["mileage_m_per_J"] =
      plant.value("energy_J", 0.0) > 0 ? plant.value("distance_m", 0.0) / plant.value("energy_J", 1.0) : 0.0;
  summary["mean_active_agents"] = plant.value("mean_active_agents", 0.0);
  summary["active_agents"] = plant.value("active_agents", nlohmann::json{{"L", act_L}, {"R", act_R}});
  summary["battery_discharge_mAh"] = plant.value("battery_discharge_mAh", nlohmann::json{{"L", 0}, {"R", 0}});
  summary["discovery_s"] = discovery_s;
  summary["discovery_server_restarts"] = ds_restarts;
  summary["transport"] = transport;
  analyse_faults(failures, plant.value("membership_events", nlohmann::json::array()), o.run_dir + "/trace.csv",
                 sc.robot.wheel_radius_m);
  summary["failures"] = failures;
  if (o.chaos_seed >= 0) summary["chaos_seed"] = o.chaos_seed;
  summary["plant"] = plant;
  summary["level2"] = level2_stats(o.run_dir);
  nlohmann::json procs = nlohmann::json::array();
  for (const auto& c : kids)
    procs.push_back({{"name", c.name},
                     {"pid", c.pid},
                     {"exit_code", c.exit_code},
                     {"signal", c.signal},
                     {"max_rss_kB", c.max_rss_kB},
                     {"starts", c.starts},
                     {"external", c.external}});
  summary["processes"] = procs;
  const std::string trace = o.run_dir + "/trace.csv";
  summary["trace_sha256"] = fs::exists(trace) ? sha256_of(trace) : "";
  summary["status"] = status;
  std::ofstream(o.run_dir + "/summary.json") << summary.dump(2) << "\n";
  log.info("run ended: {}", status);
  return summary;
}

void send_command(const std::string& run_dir, const std::string& action, const std::string& target) {
  const std::string fifo = run_dir + "/control";
  const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
  if (fd < 0) throw std::runtime_error("no fleet is running in " + run_dir + " (no reader on " + fifo + ")");
  const std::string line = action + " " + target + "\n";
  const ssize_t n = ::write(fd, line.data(), line.size());
  ::close(fd);
  if (n != static_cast<ssize_t>(line.size())) throw std::runtime_error("could not write to " + fifo);
}

std::string human_summary(const nlohmann::json& s) {
  std::ostringstream os;
  char buf[512];
  long rss_max = 0;
  double rss_sum = 0;
  for (const auto& p : s["processes"]) {
    rss_max = std::max<long>(rss_max, p.value("max_rss_kB", 0L));
    rss_sum += p.value("max_rss_kB", 0L);
  }
  std::snprintf(buf, sizeof(buf),
                "status      %s\n"
                "scenario    %s: %d agents, motor %s, %.1f kg, mode %s\n"
                "simulated   %.1f s in %.2f s wall (real-time factor %.1f); discovery %.2f s\n"
                "distance    %.1f m, energy %.1f J, mileage %.4f m/J, mean active agents %.2f\n"
                "battery     discharge L %.1f mAh, R %.1f mAh\n"
                "processes   %zu, max RSS %.1f MB (mean %.1f MB)\n"
                "trace       sha256 %s\n",
                s.value("status", "").c_str(), s.value("scenario", "").c_str(), s.value("agents", 0),
                s.value("motor", "").c_str(), s.value("gross_mass_kg", 0.0), s.value("mode", "").c_str(),
                s.value("sim_time_s", 0.0), s.value("wall_time_s", 0.0), s.value("real_time_factor", 0.0),
                s.value("discovery_s", 0.0), s.value("distance_m", 0.0), s.value("energy_J", 0.0),
                s.value("mileage_m_per_J", 0.0), s.value("mean_active_agents", 0.0),
                s["battery_discharge_mAh"].value("L", 0.0), s["battery_discharge_mAh"].value("R", 0.0),
                s["processes"].size(), rss_max / 1024.0, s["processes"].empty() ? 0.0 : rss_sum / 1024.0 / s["processes"].size(),
                s.value("trace_sha256", "").c_str());
  os << buf;
  if (s.contains("level2") && s["level2"].is_object())
    for (const auto& [side, l2] : s["level2"].items()) {
      if (l2.value("decisions", 0) == 0) continue;
      std::snprintf(buf, sizeof(buf), "level 2 %s   %d decisions, Ipopt median %.1f ms (max %.1f)%s%s\n", side.c_str(),
                    l2.value("decisions", 0), l2.value("solve_ms_median", 0.0), l2.value("solve_ms_max", 0.0),
                    l2.value("oracle_checked", 0) > 0
                        ? (", oracle differed " + std::to_string(l2.value("oracle_differs", 0)) + " of " +
                           std::to_string(l2.value("oracle_checked", 0)))
                              .c_str()
                        : "",
                    l2.value("infeasible", 0) > 0
                        ? (", infeasible " + std::to_string(l2.value("infeasible", 0)) +
                           " times: the load needs more than the live agents give, all of them ran")
                              .c_str()
                        : "");
      os << buf;
    }
  return os.str();
}

}  // namespace maptr::deploy
