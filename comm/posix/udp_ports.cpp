#include "comm/posix/udp_ports.hpp"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace maptr::comm {

namespace {

/// The inodes ("socket:[N]") of the sockets bound to `port` in a /proc/.../net/udp[6] table:
/// "sl local_address rem_address st tx:rx tr:when retrnsmt uid timeout inode ...", the local
/// address as HEXIP:HEXPORT.
void sockets_on_port(const std::string& table, int port, std::set<std::string>& inodes) {
  std::ifstream f(table);
  std::string line;
  std::getline(f, line);
  while (std::getline(f, line)) {
    std::istringstream in(line);
    std::string slot, local, remote, state, queues, timer, retransmits, uid, timeout, inode;
    in >> slot >> local >> remote >> state >> queues >> timer >> retransmits >> uid >> timeout >> inode;
    const auto colon = local.rfind(':');
    if (colon == std::string::npos) continue;
    try {
      if (std::stoi(local.substr(colon + 1), nullptr, 16) == port) inodes.insert("socket:[" + inode + "]");
    } catch (const std::exception&) {
      // a line this parser does not know: not a socket on the port
    }
  }
}

}  // namespace

bool udp_port_listed(int port) {
  std::set<std::string> inodes;
  sockets_on_port("/proc/self/net/udp", port, inodes);
  sockets_on_port("/proc/self/net/udp6", port, inodes);
  return !inodes.empty();
}

bool udp_port_bound_by(pid_t pid, int port) {
  const std::string proc = "/proc/" + std::to_string(pid);
  std::set<std::string> inodes;
  sockets_on_port(proc + "/net/udp", port, inodes);
  if (inodes.empty()) return false;
  std::error_code ec;
  for (const auto& fd : std::filesystem::directory_iterator(proc + "/fd", ec)) {
    std::error_code link_ec;
    const auto target = std::filesystem::read_symlink(fd.path(), link_ec);
    if (!link_ec && inodes.count(target.string())) return true;
  }
  return false;
}

}  // namespace maptr::comm
