// The scenario's `hosts` section: read by hand (a list of machines and placement rules), written
// back, and its fields' reference.
#include <yaml-cpp/yaml.h>

#include "config/fields.hpp"

namespace maptr::config {

namespace detail {

namespace {
/// A text value of the hosts section.
std::string host_text(const YAML::Node& v, const std::string& path, const Context& c) {
  if (!v.IsScalar()) c.fail(path, describe(v), "must be text");
  return v.Scalar();
}
}  // namespace

/// hosts: {count, launcher_address, failover, ssh, machines: [{address, command}], placement: ["NAME=hN"]}.
void read_hosts(const YAML::Node& v, HostsConfig& h, const Context& c) {
  if (!v.IsMap()) c.fail("hosts", describe(v), "must be a mapping");
  for (auto it = v.begin(); it != v.end(); ++it) {
    const std::string key = it->first.Scalar(), path = "hosts." + key;
    const YAML::Node x = it->second;  // a copy: the iterator's value is a temporary
    if (key == "count") {
      int n = 0;
      if (!x.IsScalar() || !YAML::convert<int>::decode(x, n) || n < 1 || n > kMaxHosts)
        c.fail(path, describe(x), "must be a whole number from 1 to " + std::to_string(kMaxHosts));
      h.count = n;
    } else if (key == "launcher_address") {
      h.launcher_address = host_text(x, path, c);
    } else if (key == "failover" || key == "ssh") {
      if (!x.IsScalar() || !YAML::convert<bool>::decode(x, key == "ssh" ? h.ssh : h.failover))
        c.fail(path, describe(x), "must be true or false");
    } else if (key == "placement" && x.IsSequence()) {
      for (std::size_t i = 0; i < x.size(); ++i)
        h.placement.push_back(host_text(x[i], path + "[" + std::to_string(i) + "]", c));
    } else if (key == "machines" && x.IsSequence()) {
      for (std::size_t i = 0; i < x.size(); ++i) {
        const std::string base = path + "[" + std::to_string(i) + "]";
        if (!x[i].IsMap() || !x[i]["address"])
          c.fail(base, describe(x[i]), "must be {address: IP, command: PREFIX}");
        h.machines.push_back({host_text(x[i]["address"], base + ".address", c),
                              x[i]["command"] ? host_text(x[i]["command"], base + ".command", c) : ""});
      }
    } else {
      c.fail(path, describe(x),
             "unknown key, or not a list (count, launcher_address, failover, ssh, machines, placement)");
    }
  }
  if (!h.machines.empty() && h.count == 0) h.count = static_cast<int>(h.machines.size());
  if (!h.machines.empty() && static_cast<int>(h.machines.size()) != h.count)
    c.fail("hosts.machines", std::to_string(h.machines.size()) + " machines",
           "must list one machine per host");
  if (!h.machines.empty() && h.ssh)
    c.fail("hosts.ssh", "true",
           "is the rehearsal on namespace hosts; real machines give their own ssh command");
  if (!h.machines.empty() && h.launcher_address.empty())
    c.fail("hosts.launcher_address", "(missing)",
           "real machines need the address they reach this machine at");
}

void write_hosts(const HostsConfig& h, YAML::Node& root) {
  if (!h.enabled()) return;
  root["hosts"]["count"] = h.count;
  if (!h.launcher_address.empty()) root["hosts"]["launcher_address"] = h.launcher_address;
  if (!h.failover) root["hosts"]["failover"] = false;
  if (h.ssh) root["hosts"]["ssh"] = true;
  for (const auto& m : h.machines) {
    YAML::Node n;
    n["address"] = m.address;
    n["command"] = m.command;
    n.SetStyle(YAML::EmitterStyle::Flow);
    root["hosts"]["machines"].push_back(n);
  }
  for (const auto& p : h.placement) root["hosts"]["placement"].push_back(p);
}

}  // namespace detail

std::vector<FieldInfo> host_field_table() {
  const auto info = [](const char* path, FieldType type, const char* rule, const char* description) {
    FieldInfo f;
    f.path = path;
    f.type = type;
    f.rule = rule;
    f.description = description;
    f.input_only = false;
    return f;
  };
  FieldInfo count =
      info("hosts.count", FieldType::kInteger, "",
           "hosts h0.. the fleet runs on (network namespaces of this machine, or hosts.machines); "
           "absent: every process on this machine, no namespaces");
  count.range = Range{1, static_cast<double>(kMaxHosts), false, false, false, 1};
  count.unit = "1";
  count.default_value = "0";
  FieldInfo failover =
      info("hosts.failover", FieldType::kBool, "",
           "when a host is lost (kill-host), its controllers (central, the groups) start again on "
           "a surviving host; its agents stay lost (they are the wheels on it)");
  failover.default_value = "true";
  FieldInfo ssh =
      info("hosts.ssh", FieldType::kBool, "",
           "namespace hosts as real machines: an OpenSSH server in each, a key pair made for the run, "
           "and every process started over ssh (the rehearsal of hosts.machines; needs openssh-server)");
  ssh.default_value = "false";
  return {
      count,
      info("hosts.launcher_address", FieldType::kText, "an IP address",
           "the address real machines reach the launcher at (needed with hosts.machines)"),
      failover,
      ssh,
      info("hosts.machines[].address", FieldType::kText, "an IPv4 address",
           "a real machine's address, one entry per host (without machines each host is a namespace here)"),
      info("hosts.machines[].command", FieldType::kText, "a command prefix, e.g. ssh user@board1",
           "what starts a process on that machine, which holds the binaries and run folder at this machine's "
           "paths"),
      info("hosts.placement[]", FieldType::kText, "NAME=hN, e.g. central=h1",
           "put a process on a host (the rest are spread by the launcher)")};
}

}  // namespace maptr::config
