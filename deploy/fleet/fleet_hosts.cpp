// A fleet on several hosts: the fleet's side of host placement (host_placement.hpp): the hosts'
// discovery servers, and what host faults (kill-host, partition, heal) do to the processes.
#include <csignal>

#include "deploy/fleet/fleet.hpp"

namespace maptr::deploy::fleet {

void Fleet::setup_hosts() {
  hosts_ = std::make_unique<HostPlacement>(sc_.hosts, o_.domain, log_);
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
    } else {
      a = {FaultAction::kSkip, "the bridge did not take the cut (bridge link set ... state 0)"};
    }
  } else if (f.action == "heal" && host.partitioned) {
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
    if (!hosts_->move_off_lost(*c)) {
      f.problem = "no host left that is neither lost nor cut off";
      log_.error("failover: {} of lost host {}: {}", f.name, f.from, f.problem);
      continue;
    }
    spawn_child(*c);
    c->awaiting_ready = true;
    f.to = hosts_->host(c->host).name;
    f.started = Clock::now();
    started.push_back(f.name);
    log_.warn("failover: {} of lost host {} started on {} (pid {}) at t={:.2f} s", f.name, f.from, f.to,
              c->pid, clock_.state().t);
  }
  return started;
}

void Fleet::failed_over(const Child& c) {
  for (auto& f : failovers_)
    if (f.name == c.name && !f.to.empty() && f.running_at_s < 0.0) {
      f.running_at_s = clock_.state().t;
      f.ready_wall_s = since(f.started);
    }
}

}  // namespace maptr::deploy::fleet
