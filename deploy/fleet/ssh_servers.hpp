#pragma once
// The rehearsal of real machines on namespace hosts (`maptr run --hosts N --ssh`, or the
// scenario's hosts.ssh): an OpenSSH server in each host's network namespace, listening on the
// host's address; a client key pair and a host key made for the run in ssh_dir(tag) (0700); and
// each host's command prefix an `ssh` to it with that key, checking the host key against a
// known_hosts file written for the run. The launcher then starts every process of the host
// exactly as it does for a real machine of hosts.machines. `-tt` gives each remote process a
// terminal, so that when the launcher kills its ssh the remote process gets SIGHUP and ends.
// Removed on destruction (the servers ended, the folder deleted); sweep_stale_networks() removes
// what a killed launcher left (hosts.hpp).
#include <sys/types.h>

#include <string>
#include <vector>

#include "deploy/fleet/hosts.hpp"

namespace maptr::deploy::fleet {

/// What this machine lacks for the rehearsal ("" : nothing): the server, the client, ssh-keygen.
std::string ssh_rehearsal_problem();

class SshServers {
 public:
  /// Starts a server on every host and sets each host's prefix to an ssh to it. Each server,
  /// and whatever it starts, sees a disk of its own at `run_dir` (an empty file system mounted
  /// there in a mount namespace of its own): no host sees the launcher's run folder. The login
  /// shell that runs a command on a host reads none of root's start-up files (~/.bashrc and the
  /// like are empty there, as on a fresh machine). Throws
  /// std::runtime_error (after removing what it made) when a server does not listen within 10 s.
  SshServers(std::vector<Host>& hosts, int tag, const std::string& run_dir);
  ~SshServers();
  SshServers(const SshServers&) = delete;
  SshServers& operator=(const SshServers&) = delete;
  /// The pid of host h's server.
  pid_t server(int h) const { return servers_.at(static_cast<std::size_t>(h)); }

 private:
  void remove();
  /// The server of host h (sshd -D on its address, in its namespace, on a disk of its own).
  pid_t start_server(const Host& h, const std::string& run_dir) const;
  /// The command prefix that reaches host h with the run's key, checking its host key.
  std::vector<std::string> client_prefix(const Host& h) const;
  std::string dir_;
  std::vector<pid_t> servers_;
};

}  // namespace maptr::deploy::fleet
