#include "deploy/fleet/hosts.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

extern char** environ;

namespace maptr::deploy::fleet {

namespace fs = std::filesystem;

namespace {
/// Where a run that owns namespaces keeps its lock.
constexpr const char* kLockDir = "/run/maptr-hosts";
constexpr const char* kNetnsDir = "/run/netns";
constexpr const char* kNetnsPrefix = "maptr-";
/// The launcher's host byte on the bridge, and the first host's.
constexpr int kBridgeHostByte = 254, kFirstHostByte = 1;
/// Second and third byte of the 10/8 subnets: 10.(kSubnetA0 + k % kSubnetASpan).B.
constexpr int kSubnetA0 = 200, kSubnetASpan = 50;
/// Bridge port states (the kernel's BR_STATE_*). A disabled port neither takes nor sends frames
/// and stays so; a bridge without STP turns a blocking port forwarding again at once.
constexpr const char* kPortDisabled = "0";
constexpr const char* kPortForwarding = "3";

std::string netns_name(const std::string& tag, int i) {
  return kNetnsPrefix + tag + "-h" + std::to_string(i);
}

void ip_or_throw(const std::vector<std::string>& args) {
  std::vector<std::string> argv = {"ip"};
  argv.insert(argv.end(), args.begin(), args.end());
  std::string out;
  if (run_tool(argv, &out) != 0) {
    std::string cmd;
    for (const auto& a : argv) cmd += (cmd.empty() ? "" : " ") + a;
    throw std::runtime_error("hosts: `" + cmd + "` failed: " + out);
  }
}

/// Removes the namespaces and the bridge of a tag (what is missing is skipped).
/// The pids of the processes in a namespace.
std::vector<pid_t> netns_pids(const std::string& netns) {
  std::string out;
  run_tool({"ip", "netns", "pids", netns}, &out);
  std::istringstream in(out);
  std::vector<pid_t> pids;
  for (long pid = 0; in >> pid;)
    if (pid > 1) pids.push_back(static_cast<pid_t>(pid));
  return pids;
}
}  // namespace

std::string ssh_dir(const std::string& tag) { return std::string(kLockDir) + "/" + tag + "-ssh"; }

namespace {
int remove_tag(const std::string& tag) {
  int removed = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(kNetnsDir, ec)) {
    const std::string n = e.path().filename().string();
    if (n.rfind(std::string(kNetnsPrefix) + tag + "-h", 0) != 0) continue;
    // What still runs in it is this tag's: its ssh server, or a process of a launcher killed.
    for (const pid_t pid : netns_pids(n)) ::kill(pid, SIGKILL);
    removed += run_tool({"ip", "netns", "delete", n}) == 0;  // its veth pair goes with it
  }
  run_tool({"ip", "link", "delete", "mbr" + tag});
  fs::remove_all(ssh_dir(tag), ec);
  return removed;
}

uint64_t read_counter(const std::string& path) {
  std::ifstream f(path);
  uint64_t v = 0;
  f >> v;
  return v;
}
}  // namespace

std::string hosts_root_problem() {
  if (geteuid() == 0) return "";
  return "--hosts: a fleet on several hosts makes a network namespace per host and needs root "
         "(run as root, or without --hosts)";
}

int run_tool(const std::vector<std::string>& argv, std::string* output, bool with_stderr) {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) return -1;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, fds[1], 1);
  if (with_stderr) posix_spawn_file_actions_adddup2(&fa, fds[1], 2);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, args[0], &fa, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  close(fds[1]);
  std::string out;
  char buf[512];
  for (ssize_t n; (n = read(fds[0], buf, sizeof(buf))) > 0;) out.append(buf, static_cast<std::size_t>(n));
  close(fds[0]);
  if (output) *output = out;
  if (rc != 0) return -1;
  int st = 0;
  if (waitpid(pid, &st, 0) != pid) return -1;
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

std::string shell_quote(const std::string& word) {
  std::string q = "'";
  for (char ch : word) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

bool is_ssh_prefix(const std::vector<std::string>& prefix) {
  return !prefix.empty() && fs::path(prefix[0]).filename() == "ssh";
}

std::vector<std::string> host_argv(const std::vector<std::string>& prefix, const Environment& env,
                                   const std::string& binary, const std::vector<std::string>& args,
                                   bool terminal) {
  std::vector<std::string> command = {"env"};
  for (const auto& [k, v] : env) command.push_back(k + "=" + v);
  command.push_back(binary);
  command.insert(command.end(), args.begin(), args.end());
  std::vector<std::string> out = prefix;
  if (is_ssh_prefix(prefix)) {
    // ssh joins its words with blanks for the remote shell: each is quoted to arrive as it is.
    for (auto& w : command) w = shell_quote(w);
    // -n: never the launcher's stdin (a terminal would stop a background client); -tt: a
    // terminal there, so that when the launcher ends the client the process gets SIGHUP.
    const auto has = [&](const char* o) { return std::find(out.begin(), out.end(), o) != out.end(); };
    if (!has("-n")) out.insert(out.begin() + 1, "-n");
    if (terminal && !has("-tt")) out.insert(out.begin() + 1, "-tt");
  }
  out.insert(out.end(), command.begin(), command.end());
  return out;
}

std::vector<std::string> split_command(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

std::vector<int> place_processes(const std::vector<std::string>& names, int hosts,
                                 const std::vector<std::string>& rules) {
  std::vector<int> where(names.size(), 0);
  const int controller_hosts = hosts >= 3 ? hosts - 1 : hosts;
  int controller = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    int side = 0, index = 0;
    if (config::parse_agent_name(names[i], side, index))
      where[i] = index % hosts;
    else
      where[i] = controller++ % controller_hosts;
  }
  for (const auto& rule : rules) {
    const auto eq = rule.find('=');
    const std::string name = rule.substr(0, eq);
    int host = 0;
    const auto it = std::find(names.begin(), names.end(), name);
    if (eq == std::string::npos || it == names.end() || !config::parse_host_name(rule.substr(eq + 1), host) ||
        host >= hosts)
      throw config::ScenarioError("hosts.placement: '" + rule +
                                  "': expected PROCESS=hN with a process of the fleet " + "and a host h0..h" +
                                  std::to_string(hosts - 1));
    where[static_cast<std::size_t>(it - names.begin())] = host;
  }
  return where;
}

std::string subnet_of(int tag) {
  const int k = tag & 0xffff;
  return "10." + std::to_string(kSubnetA0 + (k >> 8) % kSubnetASpan) + "." + std::to_string(k & 0xff);
}

NamespaceNet::NamespaceNet(int hosts, int tag) : tag_(std::to_string(tag)), bridge_("mbr" + tag_) {
  const std::string net = subnet_of(tag);
  bridge_address_ = net + "." + std::to_string(kBridgeHostByte);
  fs::create_directories(kLockDir);
  const std::string lock = std::string(kLockDir) + "/" + tag_ + ".lock";
  lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (lock_fd_ < 0 || flock(lock_fd_, LOCK_EX | LOCK_NB) != 0)
    throw std::runtime_error("hosts: cannot lock " + lock);
  try {
    ip_or_throw({"link", "add", bridge_, "type", "bridge"});
    ip_or_throw({"addr", "add", bridge_address_ + "/24", "dev", bridge_});
    ip_or_throw({"link", "set", bridge_, "up"});
    for (int i = 0; i < hosts; ++i) {
      Host h;
      h.name = config::host_name(i);
      h.netns = netns_name(tag_, i);
      h.veth = "mv" + tag_ + "h" + std::to_string(i);
      h.address = net + "." + std::to_string(kFirstHostByte + i);
      h.prefix = {"ip", "netns", "exec", h.netns};
      const std::string peer = "mp" + tag_ + "h" + std::to_string(i);
      ip_or_throw({"netns", "add", h.netns});
      ip_or_throw({"link", "add", h.veth, "type", "veth", "peer", "name", peer, "netns", h.netns});
      ip_or_throw({"link", "set", h.veth, "master", bridge_});
      ip_or_throw({"link", "set", h.veth, "up"});
      ip_or_throw({"-n", h.netns, "link", "set", peer, "name", "eth0"});
      ip_or_throw({"-n", h.netns, "addr", "add", h.address + "/24", "dev", "eth0"});
      ip_or_throw({"-n", h.netns, "link", "set", "eth0", "up"});
      ip_or_throw({"-n", h.netns, "link", "set", "lo", "up"});
      hosts_.push_back(h);
    }
  } catch (...) {
    remove();
    throw;
  }
}

NamespaceNet::~NamespaceNet() { remove(); }

void NamespaceNet::remove() {
  remove_tag(tag_);
  if (lock_fd_ >= 0) {
    ::unlink((std::string(kLockDir) + "/" + tag_ + ".lock").c_str());
    ::close(lock_fd_);
    lock_fd_ = -1;
  }
}

void NamespaceNet::kill_processes(int host, pid_t spare) {
  for (const pid_t pid : netns_pids(hosts_.at(static_cast<std::size_t>(host)).netns))
    if (pid != spare) ::kill(pid, SIGKILL);
}

bool NamespaceNet::set_link(int host, bool up) {
  Host& h = hosts_.at(static_cast<std::size_t>(host));
  // The host's bridge port is disabled or forwarding again, as a switch cuts a port: at once,
  // both ways. A veth taken down and up stays dead for a while after the `up` (docs/ARCHITECTURE.md,
  // host faults); iproute2 6.1's `ip link set ... type bridge_slave state 0` changes nothing.
  const char* state = up ? kPortForwarding : kPortDisabled;
  if (run_tool({"bridge", "link", "set", "dev", h.veth, "state", state}, nullptr) != 0) return false;
  std::ifstream now("/sys/class/net/" + h.veth + "/brport/state");
  std::string read;
  if (!(now >> read) || read != state) return false;  // the kernel put it back: the cut did not happen
  h.partitioned = !up;
  return true;
}

LinkBytes NamespaceNet::bytes(int host) const {
  const std::string dir = "/sys/class/net/" + hosts_.at(static_cast<std::size_t>(host)).veth + "/statistics/";
  // The bridge-side end receives what the host sends and sends what the host receives.
  return {read_counter(dir + "rx_bytes"), read_counter(dir + "tx_bytes")};
}

int sweep_stale_networks() {
  int removed = 0;
  std::error_code ec;
  std::vector<std::string> live;
  for (const auto& e : fs::directory_iterator(kLockDir, ec)) {
    if (e.path().extension() != ".lock") continue;
    const std::string tag = e.path().stem().string();
    const int fd = ::open(e.path().c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0) continue;
    if (flock(fd, LOCK_EX | LOCK_NB) == 0) {
      removed += remove_tag(tag);  // nobody holds it: its launcher is gone
      ::unlink(e.path().c_str());
    } else {
      live.push_back(tag);
    }
    ::close(fd);
  }
  // Namespaces of a tag without a lock file (a lock is taken before any namespace is made).
  for (const auto& e : fs::directory_iterator(kNetnsDir, ec)) {
    const std::string n = e.path().filename().string();
    if (n.rfind(kNetnsPrefix, 0) != 0) continue;
    const std::string tag =
        n.substr(std::string(kNetnsPrefix).size(), n.rfind("-h") - std::string(kNetnsPrefix).size());
    if (std::find(live.begin(), live.end(), tag) == live.end()) removed += remove_tag(tag);
  }
  // Bridges of a tag without a lock file nor namespaces.
  for (const auto& e : fs::directory_iterator("/sys/class/net", ec)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("mbr", 0) == 0 && std::find(live.begin(), live.end(), n.substr(3)) == live.end())
      run_tool({"ip", "link", "delete", n});
  }
  return removed;
}

}  // namespace maptr::deploy::fleet
