#include "deploy/fleet/fleet.hpp"

#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

#include "comm/dds/fleet_guid.hpp"
#include "comm/dds/fleet_ids.hpp"
#include "comm/dds/raw_type.hpp"
#include "comm/posix/environment.hpp"
#include "comm/posix/shm_files.hpp"
#include "deploy/fleet/secure_domain.hpp"
#include "deploy/fleet/shm_cleanup.hpp"
#include "records/fleet_file.hpp"
#include "records/run_files.hpp"

namespace maptr::deploy::fleet {

namespace {
/// Processes before the agents in launch order: plant, central, group-L, group-R.
constexpr std::size_t kControllers = 4;
void on_signal(int) { interrupted().store(true); }
}  // namespace

std::atomic<bool>& interrupted() {
  static std::atomic<bool> flag{false};
  return flag;
}

GuidPrefix writer_prefix(const eprosima::fastrtps::rtps::InstanceHandle_t& h) {
  const auto guid = eprosima::fastrtps::rtps::iHandle2GUID(h);
  GuidPrefix p{};
  std::copy(std::begin(guid.guidPrefix.value), std::end(guid.guidPrefix.value), p.begin());
  return p;
}

Fleet::Fleet(const LaunchOptions& o, spdlog::logger& log, const FleetConfig& cfg)
    : o_(o),
      sc_(o.scenario),
      log_(log),
      cfg_(cfg),
      cfg_path_(o.run_dir + "/scenario.yaml"),
      ids_(fleet_participants(o.scenario.robot.agents),
           (comm::rtps_max_participant_id(o.domain) + 1) / fleet_participants(o.scenario.robot.agents)),
      faults_(launcher_faults(o.scenario.faults), *this),
      stall_(o.stall_s > 0.0 ? o.stall_s : cfg.stall_s) {
  const int agents = sc_.robot.agents;
  std::filesystem::create_directories(o.run_dir + "/logs");
  std::ofstream(cfg_path_) << config::to_yaml(sc_);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  clean_shm_before_run(log);
  // Restarts cycle through as many participant-id windows as stay below port 65536.
  if ((comm::rtps_max_participant_id(o.domain) + 1) / fleet_participants(agents) < 1)
    throw std::runtime_error(domain_problem(o.domain, agents));
  // Participant ids: 0 the discovery server, 1 the launcher, then the fleet.
  dds_.domain = o.domain;
  if (!o.secure) make_discovery_servers();  // a secure domain has no discovery server (simple discovery)
  dds_.participant_id = comm::kLauncherParticipantId;
  // The fleet id makes every participant's GUID prefix say which process of this fleet it is
  // (comm/dds/fleet_guid.hpp): followers take ticks only from the plant's writer.
  dds_.fleet_id = std::random_device{}() | 1u;
  // The plant's participant, known from the fleet id and its participant id: its ticks and gates
  // are the only ones the launcher follows (an external plant is started with the same ids).
  // On a secure domain the plant's prefix comes from its certificate: learnt from its first
  // authenticated tick (learn_secure_plant).
  if (!o.secure) follow_plant(comm::kPlantParticipantId);
  dds_.lease_s = cfg.lease_s(agents);
  rec_.chaos_seed = o.chaos_seed;
  choose_transport();
  make_children();
  if (on_hosts()) hosts_->place(kids_);
  if (!ds_.empty()) {
    for (auto& ds : ds_) ds->start_or_throw(env_, ids_);
    if (!on_hosts()) dds_.discovery_server = ds_.front()->address();  // the port it listens on
    env_[comm::kEnvDiscoveryServer] = dds_.discovery_server;
  } else {
    make_secure_domain();
  }
  // On several hosts the launcher (on the bridge) registers with the plant's host's server.
  if (on_hosts()) dds_.own_server = kids_.front().host;
  domain_ = std::make_unique<LauncherParticipant>(dds_);
  start_recorder();
  t_launch_ = Clock::now();
}

void Fleet::make_discovery_servers() {
  if (sc_.hosts.enabled()) {
    setup_hosts();  // a server per host; the launcher on the hosts' network
    return;
  }
  const int agents = sc_.robot.agents;
  ds_.push_back(std::make_unique<DiscoveryServer>(o_.bin_dir + "/maptr_discovery", o_.run_dir, o_.domain,
                                                  cfg_.discovery_listen_s,
                                                  cfg_.discovery_restart_leases * cfg_.lease_s(agents)));
}

void Fleet::choose_transport() {
  const int agents = sc_.robot.agents;
  rec_.transport = o_.transport != "auto" ? o_.transport : "shm";
  // Between hosts data goes over UDP: every participant then announces both kinds of locator
  // (a peer on the same host is reached over shared memory, one on another host over UDP).
  // A secure domain's simple discovery needs every participant's default locators as well.
  if ((sc_.hosts.enabled() || o_.secure) && rec_.transport == "shm") rec_.transport = "shm+udp";
  dds_.shm = rec_.transport != "udp";
  dds_.shm_data_only = rec_.transport == "shm";
  dds_.shm_port_queue =
      static_cast<uint32_t>(cfg_.shm_port_queue(agents));  // the recorder takes every sample
  env_ = {{comm::kEnvFleetId, std::to_string(dds_.fleet_id)},
          {comm::kEnvTransport, rec_.transport},
          {comm::kEnvDomain, std::to_string(o_.domain)},
          {comm::kEnvLease, std::to_string(dds_.lease_s)},
          {comm::kEnvShmPortQueue, std::to_string(cfg_.shm_port_queue(agents))}};
  if (on_hosts()) env_[comm::kEnvPlantLoss] = std::to_string(cfg_.host_plant_loss_s);
}

Fleet::~Fleet() {
  signal_all(kids_, SIGKILL);  // only after a launch that failed half-way: end() ended them
  domain_.reset();
}

double Fleet::since(Clock::time_point t0) const {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

void Fleet::make_children() {
  const std::vector<std::string> common = {"--config", cfg_path_, "--run-dir", o_.run_dir};
  auto add = [&](const std::string& name, const std::string& bin, std::vector<std::string> extra,
                 ChildKind kind, int side, uint16_t index) {
    Child c;
    c.name = name;
    c.binary = o_.bin_dir + "/" + bin;
    c.args = common;
    c.args.insert(c.args.end(), extra.begin(), extra.end());
    c.kind = kind;
    c.side = side;
    c.index = index;
    c.base_id = comm::base_participant_id(name, sc_.robot.agents);
    c.external = std::find(o_.external.begin(), o_.external.end(), name) != o_.external.end();
    if (c.external) c.participant_id = c.base_id;  // the command it is printed with
    if (!std::filesystem::exists(c.binary)) throw std::runtime_error("missing process binary " + c.binary);
    kids_.push_back(c);
  };
  add("plant", "maptr_plant", {}, ChildKind::kPlant, 0, 0);
  add("central", "maptr_central", {}, ChildKind::kCentral, 0, 0);
  add("group-L", "maptr_group", {"--side", "L"}, ChildKind::kGroup, 0, 0);
  add("group-R", "maptr_group", {"--side", "R"}, ChildKind::kGroup, 1, 0);
  for (int s = 0; s < 2; ++s)
    for (int j = 0; j < sc_.robot.per_side(); ++j) {
      const std::string n = config::agent_name(s, j);
      add(n, "maptr_agent", {"--id", n}, ChildKind::kAgent, s, static_cast<uint16_t>(j));
    }
}

void Fleet::make_secure_domain() {
  // A private CA and one identity per process (and the launcher) in RUN_DIR/security.
  const auto t0 = Clock::now();
  const auto domain = SecureDomain::create(o_.run_dir + "/security", o_.domain);
  domain.add_identity({"launcher", comm::published_topics("launcher")});
  domain.add_identity({"recorder", {}});  // run.mcap: reads every topic, writes none
  for (const auto& c : kids_) domain.add_identity({c.name, comm::published_topics(c.name)});
  dds_.security_dir = domain.files().dir;
  env_[comm::kEnvSecurityDir] = dds_.security_dir;
  log_.info("secure domain: CA and {} identities in {} ({:.2f} s)", kids_.size() + 1, dds_.security_dir,
            since(t0));
}

void Fleet::learn_secure_plant(const eprosima::fastrtps::rtps::InstanceHandle_t& writer) {
  if (!secure() || clock_.knows_plant()) return;
  if (!comm::written_by_id(dds_.fleet_id, sc_.robot.agents, writer, comm::kPlantParticipantId)) return;
  clock_.learn_plant(writer_prefix(writer));
  log_.info("the plant's participant is authenticated: following its clock");
}

void Fleet::write_fleet() const {
  // The fleet's coordinates, for tools and for processes started by hand.
  records::FleetFile f;
  f.launcher_pid = getpid();
  f.domain = o_.domain;
  if (!ds_.empty()) {
    f.discovery_server = dds_.discovery_server;
    f.discovery_server_pid = ds_.front()->pid();
  }
  f.discovery_own = dds_.own_server;
  f.secure = secure();
  f.security_dir = dds_.security_dir;
  f.lease_s = dds_.lease_s;
  f.fleet_id = dds_.fleet_id;
  f.config = cfg_path_;
  f.run_dir = o_.run_dir;
  f.bin_dir = o_.bin_dir;
  for (const auto& c : kids_)
    f.processes.push_back({c.name, c.pid, c.external, c.base_id,
                           c.host >= 0 ? std::optional(config::host_name(c.host)) : std::nullopt,
                           c.remote_pid > 0 ? std::optional<long>(c.remote_pid) : std::nullopt});
  records::write_fleet_file(o_.run_dir, f);
}

void Fleet::spawn_child(Child& c) {
  const int id = ids_.take(c.base_id, c.starts);
  spawn(c, o_.run_dir, env_, id, c.kind == ChildKind::kAgent ? zygote_.get() : nullptr);
  // A plant started again (a rematch) has the next participant id of its window: from now on its
  // ticks and gates are the plant's (a secure plant's prefix names its certificate and stays).
  if (&c == &kids_.front() && !secure()) follow_plant(id);
}

void Fleet::follow_plant(int participant_id) {
  const auto p = comm::fleet_guid_prefix(dds_.fleet_id, participant_id);
  GuidPrefix plant{};
  std::copy(std::begin(p.value), std::end(p.value), plant.begin());
  clock_.learn_plant(plant);
}

void Fleet::spawn_wave(LaunchWaves::Range r) {
  for (std::size_t i = r.begin; i < r.end; ++i)
    if (!kids_[i].external) spawn_child(kids_[i]);
  last_wave_ = Clock::now();
  write_fleet();
}

void Fleet::print_external_commands() const {
  for (const auto& c : kids_) {
    if (!c.external) continue;
    std::string cmd;
    for (const auto& [k, v] : env_) cmd += k + "=" + v + " ";
    cmd += std::string(comm::kEnvParticipantId) + "=" + std::to_string(c.base_id) + " " + c.binary;
    for (const auto& a : c.args) cmd += " " + a;
    std::fprintf(stderr, "maptr: waiting for %s; start it with:\n  %s\n", c.name.c_str(), cmd.c_str());
    log_.info("external {}: {}", c.name, cmd);
  }
}

void Fleet::start_zygote() {
  const char* how = std::getenv(kAgentStartEnv);
  const std::string mode = how ? how : "zygote";
  if (mode != "zygote" && mode != "exec")
    throw std::invalid_argument(std::string(kAgentStartEnv) + " = " + mode + ": expected zygote or exec");
  rec_.agent_start = "exec";
  if (mode == "exec" || on_hosts()) return;
  const auto agent = std::find_if(kids_.begin(), kids_.end(), [](const Child& c) { return c.kind == ChildKind::kAgent; });
  if (agent == kids_.end()) return;
  Child probe = *agent;
  probe.name = "zygote";
  zygote_ = Zygote::start(agent->binary, child_environment(probe, env_, 0), o_.run_dir + "/logs/zygote.stderr");
  if (!zygote_) {
    log_.warn("the agents' zygote did not start: agents start with exec");
    return;
  }
  rec_.agent_start = "zygote";
  log_.info("agents fork from a zygote (pid {})", zygote_->pid());
}

void Fleet::start_processes() {
  start_zygote();
  waves_ = std::make_unique<LaunchWaves>(kids_.size(), kControllers,
                                         secure() ? cfg_.secure_wave_size : cfg_.wave_size, cfg_.wave_wait_s);
  spawn_wave(waves_->first());
  print_external_commands();
  fifo_ = std::make_unique<ControlFifo>(o_.run_dir);
  registration_ = std::make_unique<FleetRegistration>(o_.run_dir, sc_.name, o_.domain);
  log_.info("launching {} processes in waves (discovery {})", kids_.size(),
            ds_.empty() ? std::string("simple, secure domain") : "server " + dds_.discovery_server);
  if (o_.progress)
    std::fprintf(stderr, "maptr: launched %zu processes (%d agents, 2 groups, central, plant)\n",
                 kids_.size(), sc_.robot.agents);
}

/// Discovery gives up at the latest after this many times its budget in all.
constexpr double kDiscoveryCap = 4.0;

bool Fleet::discover() {
  domain_->mark_seen();
  const double timeout =
      cfg_.discovery_timeout_s(sc_.robot.agents) * (secure() ? cfg_.secure_discovery_factor : 1.0);
  last_progress_ = Clock::now();
  // The budget runs from the last process that got ready (or wave started), not from the
  // launch: a loaded machine is slower, not stuck; a hard cap of kDiscoveryCap budgets in all.
  auto last_ready = Clock::now();
  while (ready_names_.size() < kids_.size()) {
    domain_->wait_until(Clock::now() + cfg_.discovery_poll);
    const std::size_t before = ready_names_.size();
    take_ready();
    if (ready_names_.size() != before) last_progress_ = last_ready = Clock::now();
    reap(false);
    std::vector<bool> ready(kids_.size());
    for (std::size_t i = 0; i < kids_.size(); ++i)
      ready[i] = kids_[i].external || ready_names_.count(kids_[i].name);
    if (const auto r = waves_->next(ready, since(last_wave_)); !r.empty()) {
      spawn_wave(r);
      last_progress_ = last_ready = Clock::now();
      log_.info("launched agents up to {} of {}", r.end - kControllers, kids_.size() - kControllers);
    }
    if (since(last_progress_) > cfg_.rematch_s(sc_.robot.agents, secure())) rematch_unready();
    Child* dead = nullptr;
    for (std::size_t i = 0; i < waves_->started() && !dead; ++i)
      if (!kids_[i].running && !kids_[i].external) dead = &kids_[i];
    if (dead && restart_dead(*dead)) dead = nullptr, last_progress_ = Clock::now();
    if (dead || interrupted().load() || since(last_ready) > timeout || since(t_launch_) > kDiscoveryCap * timeout) {
      rec_.status = interrupted().load()
                        ? "aborted: interrupted during discovery"
                    : dead ? "aborted: a process died during discovery: " + describe_end(*dead, o_.run_dir) +
                                 " (see logs/)"
                           : std::string(kDiscoveryTimeout) + "; not ready: " + not_ready();
      break;
    }
  }
  rec_.discovery_s = since(t_launch_);
  discovered_ = true;
  return rec_.status == "ok";
}

void Fleet::start_run() {
  await_recorder();
  log_.info("all {} processes matched after {:.2f} s", kids_.size(), rec_.discovery_s);
  if (o_.progress)
    std::fprintf(stderr, "maptr: all %zu processes matched in %.2f s; starting\n", kids_.size(),
                 rec_.discovery_s);
  domain_->start();
}

void Fleet::end() {
  // The plant's last tick tells every process to end; then SIGTERM, then SIGKILL.
  const auto reap_expected = [this] { reap(true); };
  // Paused processes go on first: a stopped process handles neither the last tick nor SIGTERM.
  signal_all(kids_, SIGCONT);
  if (ds_paused_ && !ds_.empty() && ds_.front()->running()) kill(ds_.front()->pid(), SIGCONT);
  ds_paused_ = false;
  wait_all(kids_, rec_.status == "ok" ? cfg_.end_clean_s : cfg_.end_aborted_s, reap_expected);
  signal_all(kids_, SIGTERM);
  wait_all(kids_, cfg_.end_term_s, reap_expected);
  signal_all(kids_, SIGKILL);
  wait_all(kids_, cfg_.end_kill_s, reap_expected);
  if (on_hosts()) end_stranded(-1);  // a partition never healed
  if (zygote_) log_.info("the zygote forked {} agents ({} requests failed)", zygote_->forked(), zygote_->failed());
  zygote_.reset();
  if (recorder_) recorder_->stop(rec_, log_);
  registration_.reset();
  fifo_.reset();
  domain_->leave();
  if (comm::participant_left_open())
    log_.warn("Fast DDS did not delete the launcher's participants within {:.0f} s (a deadlock of Fast DDS 2.9 "
              "with security, eProsima/Fast-DDS#6502); the results are written and the launcher ends without them",
              cfg_.participant_delete_s);
  for (auto& ds : ds_) ds->stop(cfg_.discovery_term_s);  // the discovery servers go last
  if (on_hosts()) {
    hosts_->collect();  // every process has ended: the hosts' logs and files come home
    std::vector<std::string> servers;
    for (const auto& ds : ds_) servers.push_back(ds->address());
    rec_.hosts = hosts_->record(kids_, servers);
    rec_.failovers = failovers_json(failovers_);
    hosts_.reset();  // the namespaces, veths and bridge
  }
  clean_shm_after_run(o_.domain, std::max(ids_.highest(), recorder_ ? recorder_->participant_id() : -1),
                      ds_.empty() ? 0 : ds_.front()->port(), log_);
}

nlohmann::json Fleet::summary() {
  rec_.discovery_restarts = 0;
  for (const auto& ds : ds_) rec_.discovery_restarts += ds->restarts();
  rec_.last_tick = clock_.state();
  rec_.failures = faults_.schedule().records();
  auto& kinds = rec_.launcher_by_kind;  // holds the malformed fault gates counted during the run
  for (const auto& [kind, n] : rec_.ready_rejected) kinds[kind] += n;
  kinds["forged"] += clock_.rejected();  // ticks and gates not from the plant (malformed ones too)
  kinds["undecodable"] = domain_->undecodable();
  rec_.launcher_rejected = 0;
  for (const auto& [kind, n] : kinds) rec_.launcher_rejected += n;
  const nlohmann::json s = build_summary(sc_, MAPTR_SOURCE_DIR, rec_, o_.run_dir, kids_);
  records::write_json_file(records::summary_path(o_.run_dir), s);
  log_.info("run ended: {}", s.value("status", ""));
  return s;
}

}  // namespace maptr::deploy::fleet
