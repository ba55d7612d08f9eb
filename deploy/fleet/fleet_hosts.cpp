// A fleet on several hosts: the fleet's side of host placement (host_placement.hpp): the hosts'
// discovery servers, and what host faults (kill-host, partition, heal) do to the processes.
#include <csignal>
#include <fstream>
#include <iterator>

#include "deploy/fleet/fleet.hpp"

namespace maptr::deploy::fleet {

void Fleet::setup_hosts() {
  hosts_ = std::make_unique<HostPlacement>(sc_.hosts, o_.domain, o_.run_dir, log_);
  // Every host must run the binaries at this machine's paths; nothing starts when one cannot.
  std::vector<std::string> binaries;
  for (const char* b : {"maptr_discovery", "maptr_plant", "maptr_central", "maptr_group", "maptr_agent"})
    binaries.push_back(o_.bin_dir + "/" + b);
  for (int i = 0; i < hosts_->count(); ++i)
    if (const std::string problem = hosts_->missing_binary(i, binaries); !problem.empty())
      throw config::ScenarioError("host " + hosts_->host(i).name + " (" + hosts_->host(i).address +
                                  "): " + problem +
                                  "; every machine needs the binaries at this machine's paths (README \"Real "
                                  "machines\")");
  // A host with a disk of its own gets the resolved scenario in its own run folder.
  std::ifstream resolved(cfg_path_);
  hosts_->ship(std::string((std::istreambuf_iterator<char>(resolved)), std::istreambuf_iterator<char>()));
  dds_.interface_address = hosts_->launcher_address();
  // One discovery server per host; each server knows the others, each client its host's own.
  const std::string servers = hosts_->discovery_servers();
  dds_.discovery_server = servers;
  const double restart_s = cfg_.discovery_restart_leases * cfg_.lease_s(sc_.robot.agents);
  for (int i = 0; i < hosts_->count(); ++i)
    ds_.push_back(std::make_unique<DiscoveryServer>(o_.bin_dir + "/maptr_discovery", o_.run_dir, o_.domain,
                                                    cfg_.discovery_listen_s, restart_s, servers, i,
                                                    hosts_->host_template(i), hosts_->namespaces()));
  log_.info("{} hosts; discovery servers {}", hosts_->count(), servers);
}

std::vector<std::string> Fleet::apply_host_fault(const config::FaultSpec& f, double at_s) {
  const double wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::system_clock::now().time_since_epoch()).count();
  int h = -1;
  config::parse_host_name(f.target, h);
  if (h < 0 || h >= hosts_->count()) {
    faults_.schedule().record(f, at_s, wall_ms, {FaultAction::kSkip, "no such host"});
    return {};
  }
  const Host& host = hosts_->host(h);
  DiscoveryServer& ds = *ds_[static_cast<std::size_t>(h)];
  FaultAction a{FaultAction::kKill, ""};
  std::vector<std::string> on_host, killed;
  for (const auto& c : kids_)
    if (c.host == h && c.running) on_host.push_back(c.name);
  if (f.action == "kill-host" && !host.lost) {
    ds.hold();
    ds.kill_now();
    for (auto& c : kids_) {
      if (c.host != h || !c.running || c.external) continue;
      kill(c.pid, SIGKILL);
      killed.push_back(c.name);
      const bool controller = c.kind == ChildKind::kCentral || c.kind == ChildKind::kGroup;
      if (controller && sc_.hosts.failover) failovers_.push_back({c.name, host.name, "", at_s});
    }
    hosts_->lose(h);
    log_.warn("fault: host {} killed at t={:.2f} s ({} processes)", host.name, at_s, killed.size());
  } else if (f.action == "partition" && !host.partitioned && hosts_->namespaces()) {
    if (hosts_->cut_off(h)) {
      // The plant stops waiting for them at this tick; they are re-admitted when they answer again.
      for (const auto& c : kids_)
        if (c.host == h && c.running && &c != &kids_.front()) publish_member(c, msg::MEMBER_DIED);
      log_.warn("fault: host {} cut off at t={:.2f} s", host.name, at_s);
      if (sc_.hosts.failover) strand_controllers(h, at_s);
    } else {
      a = {FaultAction::kSkip, "the bridge did not take the cut (bridge link set ... state 0)"};
    }
  } else if (f.action == "heal" && host.partitioned) {
    end_stranded(h);  // before the link is back
    if (hosts_->heal(h)) ds.release();
    log_.warn("fault: host {} linked again at t={:.2f} s", host.name, at_s);
  } else {
    a = {FaultAction::kSkip, hosts_->namespaces() ? "host not in a state for this action"
                                                  : "a real machine's link is not the launcher's to cut"};
  }
  faults_.schedule().record(f, at_s, wall_ms, a);
  faults_.schedule().annotate_last("processes", on_host);
  return killed;
}

std::vector<std::string> Fleet::fail_over() {
  std::vector<std::string> started;
  if (plant_done_) return started;  // the run is over (the plant's own host may be the lost one)
  for (auto& f : failovers_) {
    if (!f.to.empty() || !f.problem.empty()) continue;
    Child* c = find(f.name);
    if (!c || c->running) continue;  // not reaped yet
    const Host& was = hosts_->host(c->host);
    const bool reachable = !was.lost && !was.partitioned;  // healed meanwhile: it starts there again
    if (!reachable && !hosts_->move_off_unreachable(*c)) {
      f.problem = "no host left that is neither lost nor cut off";
      log_.error("failover: {} of host {}: {}", f.name, f.from, f.problem);
      continue;
    }
    spawn_child(*c);
    c->awaiting_ready = true;
    f.to = hosts_->host(c->host).name;
    f.started = Clock::now();
    started.push_back(f.name);
    log_.warn("failover: {} of host {} started on {} (pid {}) at t={:.2f} s", f.name, f.from, f.to, c->pid,
              clock_.state().t);
  }
  return started;
}

void Fleet::strand_controllers(int h, double at_s) {
  // A cut-off host's controllers are out of the launcher's reach as a lost one's: the plant has
  // stopped waiting for them at this tick, and new copies start on a reachable host. The old
  // copies run on where they are, stranded, until the heal. With no reachable host to go to
  // they stay, and rejoin at the heal.
  if (!hosts_->reachable_besides(h)) return;
  for (auto& c : kids_) {
    const bool controller = c.kind == ChildKind::kCentral || c.kind == ChildKind::kGroup;
    if (c.host != h || !c.running || c.external || !controller) continue;
    stranded_.push_back({h, c.pid, c.name, is_ssh_prefix(c.prefix) ? c.remote_pid : -1, c.binary});
    c.running = false;
    c.paused = false;
    failovers_.push_back({c.name, hosts_->host(h).name, "", at_s});
  }
}

void Fleet::end_stranded(int h) {
  // Before the link is back, so that a stranded copy never meets the fleet again: its process
  // on this machine (the copy on a namespace host, the ssh client over ssh) and, over ssh, the
  // copy itself by the pid its NodeReady gave. A partition exists only for namespace hosts, whose
  // processes share this machine's pids; each is checked to be still the copy before its end.
  for (auto it = stranded_.begin(); it != stranded_.end();) {
    if (h >= 0 && it->host != h) {
      ++it;
      continue;
    }
    if (it->pid > 1) ::kill(it->pid, SIGKILL);  // a child not reaped yet: its pid is still its own
    const bool remote = runs_binary(it->remote_pid, it->binary);
    if (remote) ::kill(it->remote_pid, SIGKILL);
    log_.warn("{}: the stranded copy on {} ended (pid {}{})", it->name, hosts_->host(it->host).name, it->pid,
              remote ? ", on the host " + std::to_string(it->remote_pid) : std::string());
    it = stranded_.erase(it);
  }
}

void Fleet::forget_stranded(pid_t pid) {
  for (auto& s : stranded_)
    if (s.pid == pid) s.pid = -1;  // reaped: its pid may be reused
}

void Fleet::failed_over(const Child& c) {
  for (auto& f : failovers_)
    if (f.name == c.name && !f.to.empty() && f.running_at_s < 0.0) {
      f.running_at_s = clock_.state().t;
      f.ready_wall_s = since(f.started);
    }
}

}  // namespace maptr::deploy::fleet
