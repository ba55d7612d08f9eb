#include "deploy/fleet/ssh_servers.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <thread>

#include "deploy/fleet/children.hpp"

namespace maptr::deploy::fleet {

namespace fs = std::filesystem;

namespace {
constexpr const char* kSshd = "/usr/sbin/sshd";
constexpr int kPort = 22;
constexpr auto kListenWait = std::chrono::seconds(10);

std::string first_two_words(const std::string& path) {
  std::ifstream in(path);
  std::string type, key;
  in >> type >> key;
  return type + " " + key;
}

bool accepts(const std::string& address) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(kPort);
  ::inet_pton(AF_INET, address.c_str(), &a.sin_addr);
  const bool ok = ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  ::close(fd);
  return ok;
}

/// This process's environment, for a server started with it.
std::vector<std::string> this_environment() {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) env.emplace_back(*e);
  return env;
}
}  // namespace

std::string ssh_rehearsal_problem() {
  if (::access(kSshd, X_OK) != 0) return std::string(kSshd) + " is missing (Debian: openssh-server)";
  for (const char* tool : {"ssh", "ssh-keygen"})
    if (run_tool({"sh", "-c", std::string("command -v ") + tool}) != 0)
      return std::string(tool) + " is missing (Debian: openssh-client)";
  return "";
}

SshServers::SshServers(std::vector<Host>& hosts, int tag, const std::string& run_dir)
    : dir_(ssh_dir(std::to_string(tag))) {
  if (const std::string p = ssh_rehearsal_problem(); !p.empty()) throw std::runtime_error("--ssh: " + p);
  fs::remove_all(dir_);
  fs::create_directories(dir_);
  ::chmod(dir_.c_str(), 0700);
  fs::create_directories("/run/sshd");  // the server's privilege separation folder
  fs::create_directories(run_dir);      // where each host's own disk is mounted
  for (const char* key : {"client", "host"})
    if (run_tool({"ssh-keygen", "-q", "-t", "ed25519", "-N", "", "-C", "maptr", "-f", dir_ + "/" + key}) !=
        0) {
      remove();
      throw std::runtime_error("--ssh: ssh-keygen could not make a key in " + dir_);
    }
  fs::copy_file(dir_ + "/client.pub", dir_ + "/authorized_keys");
  std::ofstream known(dir_ + "/known_hosts");
  std::ofstream conf(dir_ + "/sshd_config");
  conf << "Port " << kPort << "\nHostKey " << dir_ << "/host\nAuthorizedKeysFile " << dir_
       << "/authorized_keys\nPermitRootLogin prohibit-password\nPasswordAuthentication no\n"
          "KbdInteractiveAuthentication no\nUsePAM no\nStrictModes no\nPidFile none\nPrintMotd no\n"
          "MaxStartups 1000:30:2000\nMaxSessions 1000\n";
  conf.close();
  const std::string host_key = first_two_words(dir_ + "/host.pub");
  for (auto& h : hosts) {
    known << h.address << " " << host_key << "\n";
    servers_.push_back(start_server(h, run_dir));
    h.prefix = client_prefix(h);
  }
  known.close();
  const auto deadline = std::chrono::steady_clock::now() + kListenWait;
  for (const auto& h : hosts)
    while (!accepts(h.address)) {
      if (std::chrono::steady_clock::now() > deadline) {
        remove();
        throw std::runtime_error("--ssh: the ssh server of " + h.name + " did not listen on " + h.address +
                                 ":22 within 10 s");
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
}

pid_t SshServers::start_server(const Host& h, const std::string& run_dir) const {
  // Started as every child of the launcher is (its own process group, gone with the launcher),
  // in a mount namespace of its own with a fresh tmpfs at the run folder's path: the host's
  // disk, gone with the namespace when its server ends (or is killed with the launcher). The
  // login shell that runs each command there reads none of this machine's start-up files (they
  // are empty on the host, as on a fresh machine): what this machine's own shell set-up does,
  // however slow or broken, takes no part in the rehearsal.
  const std::string host_disk = "mount -t tmpfs -o mode=0755 maptr-$1 \"$2\" || exit 1";
  const std::string fresh_shell =
      "home=$(getent passwd root | cut -d: -f6); "
      "for f in .bashrc .bash_profile .bash_login .profile .zshenv .zshrc; do "
      "if [ -f \"$home/$f\" ]; then mount --bind /dev/null \"$home/$f\" || exit 1; fi; done";
  // clang-format off
  const std::vector<std::string> argv = {
      "ip", "netns", "exec", h.netns,
      "unshare", "--mount", "--propagation", "private",
      "sh", "-c", host_disk + "; " + fresh_shell + "; shift 2 && exec \"$@\"", "sh", h.name, run_dir,
      kSshd, "-D", "-e", "-f", dir_ + "/sshd_config", "-o", "ListenAddress=" + h.address};
  // clang-format on
  return start_process(argv, this_environment(), dir_ + "/sshd-" + h.name + ".log", -1);
}

std::vector<std::string> SshServers::client_prefix(const Host& h) const {
  // Nothing of root's own ssh set-up (its configuration, its agent's keys) takes part.
  // clang-format off
  return {"ssh", "-F", "/dev/null", "-i", dir_ + "/client", "-o", "IdentitiesOnly=yes", "-o", "BatchMode=yes",
          "-o", "ConnectTimeout=10", "-o", "UserKnownHostsFile=" + dir_ + "/known_hosts",
          "-o", "StrictHostKeyChecking=yes", "-o", "LogLevel=ERROR", "root@" + h.address};
  // clang-format on
}

SshServers::~SshServers() { remove(); }

void SshServers::remove() {
  for (const pid_t pid : servers_) {
    // Still this run's server (not reaped by the launcher's wait and its pid reused)?
    std::ifstream f("/proc/" + std::to_string(pid) + "/cmdline");
    const std::string cmd((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (pid <= 1 || cmd.find(dir_) == std::string::npos) continue;
    ::kill(pid, SIGTERM);
    for (int i = 0; i < 200 && ::waitpid(pid, nullptr, WNOHANG) == 0; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  servers_.clear();
  std::error_code ec;
  fs::remove_all(dir_, ec);
}

}  // namespace maptr::deploy::fleet
