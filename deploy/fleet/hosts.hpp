#pragma once
// The hosts of a fleet spread over several: where each process runs, how it is started there,
// and, on one machine, the network that stands for the hosts.
//
// On one machine each host hN is a Linux network namespace maptr-TAG-hN with one veth pair: one
// end (eth0, address 10.A.B.(N+1)/24) in the namespace, the other (mvTAGhN) on a bridge mbrTAG
// that carries 10.A.B.254, the launcher's address. TAG is the launcher's pid; A.B derive from it.
// A process is placed on a host by a command prefix (`ip netns exec maptr-TAG-hN`, or for a real
// machine e.g. `ssh user@board1`) followed by `env K=V ...` and the process's own command line, so
// that both kinds of host take the same path. While a run owns namespaces it holds an flock on
// /run/maptr-hosts/TAG.lock; sweep_stale_networks() removes the namespaces and bridges of every
// tag whose lock nobody holds (a launcher that was killed).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "deploy/fleet/children.hpp"

namespace maptr::deploy::fleet {

/// Why this process cannot run a fleet on namespace hosts (not root), or "".
std::string hosts_root_problem();

/// One host of the run.
struct Host {
  std::string name;                 ///< h0, h1, ...
  std::string address;              ///< its IPv4 address
  std::vector<std::string> prefix;  ///< command prefix that starts a process there
  std::string netns, veth;          ///< namespace hosts: the namespace and the bridge-side veth
  bool lost = false;                ///< killed (kill-host) and not healed
  bool partitioned = false;         ///< its link is down (partition, kill-host)
};

/// Bytes a host sent and received on its link.
struct LinkBytes {
  uint64_t sent = 0, received = 0;
};

/// The command line of a process on a host: prefix, `env`, the environment as K=V, then the
/// binary and its arguments. Over ssh with `terminal` (a process of the fleet), the remote end
/// gets a terminal, so that it ends when its ssh client does; without (a tool whose output is
/// data, e.g. a tar stream), its stdout arrives byte for byte.
std::vector<std::string> host_argv(const std::vector<std::string>& prefix, const Environment& env,
                                   const std::string& binary, const std::vector<std::string>& args,
                                   bool terminal = true);

/// `word` in single quotes for a POSIX shell (a ' inside as '\'').
std::string shell_quote(const std::string& word);
/// The prefix starts the process over ssh: the words after it are quoted for the remote shell.
bool is_ssh_prefix(const std::vector<std::string>& prefix);
/// The folder of a run's ssh rehearsal keys and configuration (ssh_servers.hpp).
std::string ssh_dir(const std::string& tag);

/// A command prefix from text, split at blanks ("ssh -o BatchMode=yes pi@10.0.0.7").
std::vector<std::string> split_command(const std::string& text);

/// The host index of every process (names in launch order: plant, central, group-L, group-R,
/// then the agents L0.., R0..) on `hosts` hosts. Default: the controllers round-robin over the
/// first hosts-1 hosts (all of them with fewer than 3), so the last host carries agents only;
/// the agents of each side round-robin over every host. Each rule "NAME=hN" overrides one
/// process. Throws config::ScenarioError naming a bad rule.
std::vector<int> place_processes(const std::vector<std::string>& names, int hosts,
                                 const std::vector<std::string>& rules);

/// The private /24 of a namespace network with this tag: "10.A.B".
std::string subnet_of(int tag);

/// The network namespaces, veths and bridge of one run on this machine (see the file comment);
/// removed on destruction.
class NamespaceNet {
 public:
  /// Creates `hosts` namespace hosts for the tag (the launcher's pid). Throws std::runtime_error
  /// (after removing what it made) if a step fails.
  NamespaceNet(int hosts, int tag);
  ~NamespaceNet();
  NamespaceNet(const NamespaceNet&) = delete;
  NamespaceNet& operator=(const NamespaceNet&) = delete;

  const std::vector<Host>& hosts() const { return hosts_; }
  std::vector<Host>& hosts() { return hosts_; }
  const std::string& bridge_address() const { return bridge_address_; }
  /// Cuts the host's link or links it again (false: the bridge did not take the change).
  bool set_link(int host, bool up);
  /// Ends (SIGKILL) every process in the host's namespace but `spare`.
  void kill_processes(int host, pid_t spare);
  /// Bytes the host sent and received on its link so far.
  LinkBytes bytes(int host) const;

 private:
  void remove();
  std::string tag_, bridge_, bridge_address_;
  std::vector<Host> hosts_;
  int lock_fd_ = -1;
};

/// Removes the namespaces, veths and bridges that runs which no longer live left behind;
/// returns how many namespaces went.
int sweep_stale_networks();

/// Runs a command (argv[0] looked up in PATH), stdout (and, with `with_stderr`, stderr) into
/// *output if given; returns its exit status (-1 if it could not run).
int run_tool(const std::vector<std::string>& argv, std::string* output = nullptr, bool with_stderr = true);

}  // namespace maptr::deploy::fleet
