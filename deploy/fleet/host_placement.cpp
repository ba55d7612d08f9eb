#include "deploy/fleet/host_placement.hpp"

#include <unistd.h>

#include <fstream>

#include "comm/posix/environment.hpp"
#include "deploy/fleet/discovery.hpp"

namespace maptr::deploy::fleet {

nlohmann::json failovers_json(const std::vector<Failover>& fs) {
  nlohmann::json out = nlohmann::json::array();
  const auto time = [](double t) { return t >= 0.0 ? nlohmann::json(t) : nlohmann::json(nullptr); };
  for (const auto& f : fs) {
    nlohmann::json j = {{"name", f.name},
                        {"from", f.from},
                        {"to", f.to.empty() ? nlohmann::json(nullptr) : nlohmann::json(f.to)},
                        {"detected_at_s", f.detected_at_s},
                        {"running_at_s", time(f.running_at_s)},
                        {"ready_wall_s", time(f.ready_wall_s)}};
    if (!f.problem.empty()) j["problem"] = f.problem;
    out.push_back(j);
  }
  return out;
}

HostPlacement::HostPlacement(const config::HostsConfig& hc, int domain, const std::string& run_dir,
                             spdlog::logger& log)
    : hc_(hc), domain_(domain), log_(log), run_dir_(run_dir) {
  if (hc.machines.empty()) {
    if (const int stale = sweep_stale_networks(); stale > 0)
      log_.info("removed {} network namespaces left by earlier runs", stale);
    net_ = std::make_unique<NamespaceNet>(hc.count, static_cast<int>(getpid()));
    hosts_ = net_->hosts();
    if (hc.ssh) {
      ssh_ = std::make_unique<SshServers>(hosts_, static_cast<int>(getpid()), run_dir);
      log_.info("{} ssh servers listening; every process starts over ssh", hosts_.size());
    }
    launcher_address_ = net_->bridge_address();
    return;
  }
  for (int i = 0; i < hc.count; ++i) {
    const auto& m = hc.machines[static_cast<std::size_t>(i)];
    Host h;
    h.name = config::host_name(i);
    h.address = m.address;
    h.prefix = split_command(m.command);
    hosts_.push_back(h);
  }
  launcher_address_ = hc.launcher_address;
}

HostPlacement::~HostPlacement() = default;

std::string HostPlacement::discovery_servers() const {
  std::string servers;
  for (const auto& h : hosts_)
    servers += (servers.empty() ? "" : ",") + h.address + ":" + std::to_string(host_discovery_port(domain_));
  return servers;
}

Child HostPlacement::host_template(int h) const {
  Child c;
  c.host = h;
  c.prefix = host(h).prefix;
  c.host_env = {{comm::kEnvInterface, host(h).address}, {comm::kEnvDiscoveryOwn, std::to_string(h)}};
  return c;
}

std::string HostPlacement::missing_binary(int h, const std::vector<std::string>& binaries) const {
  if (host(h).prefix.empty()) return "";
  constexpr const char* kMark = "maptr-missing: ";
  std::vector<std::string> args = {
      "-c", std::string("for b; do test -x \"$b\" || { echo \"") + kMark + "$b\"; exit 1; }; done", "sh"};
  args.insert(args.end(), binaries.begin(), binaries.end());
  std::string out;
  const int rc = run_tool(host_argv(host(h).prefix, {}, "sh", args), &out);
  if (rc == 0) return "";
  const auto at = out.find(kMark);
  if (at == std::string::npos) {
    const auto end = out.find_first_of("\r\n");
    return "cannot run a command there (exit " + std::to_string(rc) +
           (out.empty() ? "" : ": " + out.substr(0, end)) + ")";
  }
  const std::string rest = out.substr(at + std::string(kMark).size());
  return rest.substr(0, rest.find_first_of("\r\n")) + ": missing or not executable there";
}

namespace {
void put_on(Child& c, const Child& t) {
  c.host = t.host;
  c.prefix = t.prefix;
  c.host_env = t.host_env;
}
}  // namespace

void HostPlacement::place(std::vector<Child>& kids) const {
  std::vector<std::string> names;
  for (const auto& c : kids) names.push_back(c.name);
  const std::vector<int> where = place_processes(names, count(), hc_.placement);
  for (std::size_t i = 0; i < kids.size(); ++i) put_on(kids[i], host_template(where[i]));
}

bool HostPlacement::move_off_unreachable(Child& c) const {
  if (c.host < 0 || !(host(c.host).lost || host(c.host).partitioned)) return false;
  for (int k = 1; k < count(); ++k) {
    const int h = (c.host + k) % count();
    if (host(h).lost || host(h).partitioned) continue;
    log_.info("{}: its host {} is {}; it starts on {}", c.name, config::host_name(c.host),
              host(c.host).lost ? "lost" : "cut off", host(h).name);
    put_on(c, host_template(h));
    return true;
  }
  return false;
}

bool HostPlacement::reachable_besides(int h) const {
  for (int k = 0; k < count(); ++k)
    if (k != h && !host(k).lost && !host(k).partitioned) return true;
  return false;
}

void HostPlacement::lose(int h) {
  Host& host = hosts_.at(static_cast<std::size_t>(h));
  if (net_ && !net_->set_link(h, false)) log_.error("fault: host {}: its link could not be cut", host.name);
  // Over ssh the launcher's kills end only its ssh clients; the machine's own processes (all but
  // its ssh server, which a healed host needs) end with it.
  if (ssh_) net_->kill_processes(h, ssh_->server(h));
  host.lost = host.partitioned = true;
}

bool HostPlacement::cut_off(int h) {
  if (!net_ || !net_->set_link(h, false)) return false;
  hosts_.at(static_cast<std::size_t>(h)).partitioned = true;
  return true;
}

bool HostPlacement::heal(int h) {
  Host& host = hosts_.at(static_cast<std::size_t>(h));
  if (net_ && !net_->set_link(h, true))
    log_.error("fault: host {}: its link could not be restored", host.name);
  const bool was_lost = host.lost;
  host.partitioned = host.lost = false;
  return was_lost;
}

nlohmann::json HostPlacement::record(const std::vector<Child>& kids,
                                     const std::vector<std::string>& servers) const {
  nlohmann::json out = nlohmann::json::array();
  for (int i = 0; i < count(); ++i) {
    nlohmann::json procs = nlohmann::json::array();
    for (const auto& c : kids)
      if (c.host == i) procs.push_back(c.name);
    nlohmann::json h = {
        {"name", host(i).name},
        {"address", host(i).address},
        {"kind", net_ ? "namespace" : "machine"},
        {"started_by", host(i).prefix.empty() ? "" : host(i).prefix.front()},
        {"processes", procs},
        {"discovery_server", servers.at(static_cast<std::size_t>(i))},
        {"run_folder", files_.size() > static_cast<std::size_t>(i) ? files_[static_cast<std::size_t>(i)]
                                                                   : "the launcher's"},
        {"bytes_sent", nullptr},
        {"bytes_received", nullptr}};
    if (net_) {
      const LinkBytes b = net_->bytes(i);
      h["bytes_sent"] = b.sent;
      h["bytes_received"] = b.received;
    }
    out.push_back(h);
  }
  return out;
}

void HostPlacement::ship(const std::string& scenario_text) {
  std::ofstream(run_dir_ + "/" + kLauncherMarker) << getpid() << "\n";
  disks_.assign(hosts_.size(), HostDisk::kSame);
  files_.assign(hosts_.size(), "the launcher's");
  for (std::size_t i = 0; i < hosts_.size(); ++i) {
    const std::string problem =
        ship_run_files(hosts_[i].prefix, run_dir_, {{"scenario.yaml", scenario_text}}, disks_[i]);
    if (!problem.empty())
      throw config::ScenarioError("host " + hosts_[i].name + " (" + hosts_[i].address + "): " + problem);
    if (disks_[i] == HostDisk::kShared) files_[i] = "the launcher's, through a shared disk";
    if (disks_[i] == HostDisk::kOwn) {
      files_[i] = "its own, not collected";
      log_.info("{}: a run folder of its own; the scenario shipped to it", hosts_[i].name);
    }
  }
}

void HostPlacement::collect() {
  for (std::size_t i = 0; i < disks_.size(); ++i) {
    if (disks_[i] != HostDisk::kOwn) continue;
    if (net_ && hosts_[i].partitioned) {  // the launcher cut its link: no copy could get through
      files_[i] = std::string("its own: not collected: its link is down at the end (") +
                  (hosts_[i].lost ? "lost" : "cut off") + ")";
      log_.info("{}'s run folder, {}", hosts_[i].name, files_[i]);
      continue;
    }
    files_[i] =
        "its own: " + collect_run_files(hosts_[i].prefix, run_dir_, hosts_[i].name, {"scenario.yaml"});
    log_.info("{}'s run folder, {}", hosts_[i].name, files_[i]);
  }
}

}  // namespace maptr::deploy::fleet
