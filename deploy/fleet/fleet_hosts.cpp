// A fleet on several hosts: the hosts and their discovery servers, where each process runs,
// host faults (kill-host, partition, heal) and the hosts' part of the summary.
#include <unistd.h>

#include <csignal>

#include "comm/posix/environment.hpp"
#include "deploy/fleet/fleet.hpp"

namespace maptr::deploy::fleet {

namespace {
/// The settings a process on host h gets from the host: its command prefix, UDP interface and
/// discovery server (its host's own; comm::DdsOptions::own_server says why).
Child host_template(const Host& h, int index) {
  Child c;
  c.host = index;
  c.prefix = h.prefix;
  c.host_env = {{comm::kEnvInterface, h.address}, {comm::kEnvDiscoveryOwn, std::to_string(index)}};
  return c;
}
}  // namespace

void Fleet::setup_hosts() {
  const config::HostsConfig& hc = sc_.hosts;
  if (hc.machines.empty()) {
    if (const int stale = sweep_stale_networks(); stale > 0)
      log_.info("removed {} network namespaces left by earlier runs", stale);
    net_ = std::make_unique<NamespaceNet>(hc.count, static_cast<int>(getpid()));
    hosts_ = net_->hosts();
    dds_.interface_address = net_->bridge_address();
  } else {
    for (int i = 0; i < hc.count; ++i) {
      const auto& m = hc.machines[static_cast<std::size_t>(i)];
      Host h;
      h.name = config::host_name(i);
      h.address = m.address;
      h.prefix = split_command(m.command);
      hosts_.push_back(h);
    }
    dds_.interface_address = hc.launcher_address;
  }
  // One discovery server per host; each server knows the others, each client its host's own.
  std::string servers;
  for (const auto& h : hosts_)
    servers +=
        (servers.empty() ? "" : ",") + h.address + ":" + std::to_string(host_discovery_port(o_.domain));
  dds_.discovery_server = servers;
  const double restart_s = cfg_.discovery_restart_leases * cfg_.lease_s(sc_.robot.agents);
  for (std::size_t i = 0; i < hosts_.size(); ++i)
    ds_.push_back(std::make_unique<DiscoveryServer>(
        o_.bin_dir + "/maptr_discovery", o_.run_dir, o_.domain, cfg_.discovery_listen_s, restart_s, servers,
        static_cast<int>(i), host_template(hosts_[i], static_cast<int>(i)), net_ != nullptr));
  log_.info("{} hosts; discovery servers {}", hosts_.size(), servers);
}

void Fleet::place_children() {
  std::vector<std::string> names;
  for (const auto& c : kids_) names.push_back(c.name);
  const std::vector<int> where = place_processes(names, static_cast<int>(hosts_.size()), sc_.hosts.placement);
  for (std::size_t i = 0; i < kids_.size(); ++i) {
    const Child t = host_template(hosts_[static_cast<std::size_t>(where[i])], where[i]);
    kids_[i].host = t.host;
    kids_[i].prefix = t.prefix;
    kids_[i].host_env = t.host_env;
  }
}

void Fleet::move_off_lost_host(Child& c) {
  if (c.host < 0 || !hosts_[static_cast<std::size_t>(c.host)].lost) return;
  const int n = static_cast<int>(hosts_.size());
  for (int k = 1; k < n; ++k) {
    const int h = (c.host + k) % n;
    const Host& host = hosts_[static_cast<std::size_t>(h)];
    if (host.lost || host.partitioned) continue;
    log_.info("{}: its host {} is lost; it starts on {}", c.name, config::host_name(c.host), host.name);
    const Child t = host_template(host, h);
    c.host = t.host;
    c.prefix = t.prefix;
    c.host_env = t.host_env;
    return;
  }
}

std::vector<std::string> Fleet::apply_host_fault(const config::FaultSpec& f, double at_s) {
  const double wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::system_clock::now().time_since_epoch()).count();
  int h = -1;
  config::parse_host_name(f.target, h);
  FaultAction a{FaultAction::kKill, ""};
  std::vector<std::string> on_host, killed;
  if (h < 0 || h >= static_cast<int>(hosts_.size())) {
    schedule_.record(f, at_s, wall_ms, {FaultAction::kSkip, "no such host"});
    return {};
  }
  Host& host = hosts_[static_cast<std::size_t>(h)];
  for (const auto& c : kids_)
    if (c.host == h && c.running) on_host.push_back(c.name);
  if (f.action == "kill-host" && !host.lost) {
    ds_[static_cast<std::size_t>(h)]->hold();
    ds_[static_cast<std::size_t>(h)]->kill_now();
    for (auto& c : kids_)
      if (c.host == h && c.running && !c.external) kill(c.pid, SIGKILL), killed.push_back(c.name);
    if (net_ && !net_->set_link(h, false)) log_.error("fault: host {}: its link could not be cut", host.name);
    host.lost = host.partitioned = true;
    log_.warn("fault: host {} killed at t={:.2f} s ({} processes)", host.name, at_s, killed.size());
  } else if (f.action == "partition" && !host.partitioned && net_) {
    if (net_->set_link(h, false)) {
      host.partitioned = true;
      // The plant stops waiting for them at this tick; they are re-admitted when they answer again.
      for (const auto& c : kids_)
        if (c.host == h && c.running && &c != &kids_.front()) publish_member(c, msg::MEMBER_DIED);
      log_.warn("fault: host {} cut off at t={:.2f} s", host.name, at_s);
    } else {
      a = {FaultAction::kSkip, "the bridge did not take the cut (bridge link set ... state 0)"};
    }
  } else if (f.action == "heal" && host.partitioned) {
    if (net_ && !net_->set_link(h, true)) log_.error("fault: host {}: its link could not be restored", host.name);
    host.partitioned = false;
    if (host.lost) ds_[static_cast<std::size_t>(h)]->release();
    host.lost = false;
    log_.warn("fault: host {} linked again at t={:.2f} s", host.name, at_s);
  } else {
    a = {FaultAction::kSkip,
         net_ ? "host not in a state for this action" : "a real machine's link is not the launcher's to cut"};
  }
  schedule_.record(f, at_s, wall_ms, a);
  schedule_.annotate_last("processes", on_host);
  return killed;
}

void Fleet::record_hosts() {
  rec_.hosts = nlohmann::json::array();
  for (std::size_t i = 0; i < hosts_.size(); ++i) {
    nlohmann::json procs = nlohmann::json::array();
    for (const auto& c : kids_)
      if (c.host == static_cast<int>(i)) procs.push_back(c.name);
    nlohmann::json h = {{"name", hosts_[i].name},
                        {"address", hosts_[i].address},
                        {"kind", net_ ? "namespace" : "machine"},
                        {"processes", procs},
                        {"discovery_server", ds_[i]->address()}};
    if (net_) {
      const LinkBytes b = net_->bytes(static_cast<int>(i));
      h["bytes_sent"] = b.sent;
      h["bytes_received"] = b.received;
    } else {
      h["bytes_sent"] = nullptr;
      h["bytes_received"] = nullptr;
    }
    rec_.hosts.push_back(h);
  }
}

}  // namespace maptr::deploy::fleet
