#include "comm/posix/shm_files.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <vector>

namespace maptr::comm {

namespace fs = std::filesystem;

namespace {

/// Every file path mapped by a process whose maps this user may read; returns how many
/// processes could not be read.
int mapped_paths(std::set<std::string>& out) {
  int unreadable = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator("/proc", ec)) {
    const std::string pid = e.path().filename().string();
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream maps(e.path() / "maps");
    if (!maps) {
      if (fs::exists(e.path(), ec)) ++unreadable;  // not merely exited in between
      continue;
    }
    std::string line;
    while (std::getline(maps, line)) {
      const auto slash = line.find('/');
      if (slash == std::string::npos) continue;
      std::string path = line.substr(slash);
      const std::string deleted = " (deleted)";
      if (path.size() > deleted.size() &&
          path.compare(path.size() - deleted.size(), deleted.size(), deleted) == 0)
        path.resize(path.size() - deleted.size());
      out.insert(path);
    }
  }
  return unreadable;
}

/// Whether some process holds a flock on `path` (as Fast DDS does on a live port's `_el`).
bool flocked(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool held = ::flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);  // releases the lock if we took it
  return held;
}

/// "fastrtps_port7413", "fastrtps_port7413_el", "sem.fastrtps_port7413_mutex" -> 7413; else -1.
int port_of(const std::string& name) {
  std::string rest;
  if (name.rfind("fastrtps_port", 0) == 0)
    rest = name.substr(13);
  else if (name.rfind("sem.fastrtps_port", 0) == 0)
    rest = name.substr(17);
  else
    return -1;
  const auto digits = rest.find_first_not_of("0123456789");
  const std::string n = rest.substr(0, digits);
  if (n.empty() || n.size() > 6) return -1;  // ports have at most 5 digits
  const std::string tail = digits == std::string::npos ? "" : rest.substr(digits);
  const bool sem = name[0] == 's';
  if (sem ? tail == "_mutex" : (tail.empty() || tail == "_el")) return std::stoi(n);
  return -1;
}

}  // namespace

std::set<int> rtps_ports(int domain, int max_participant_id) {
  const int base = rtps_domain_port_base(domain);
  std::set<int> ports = {base, base + 1};
  for (int id = 0; id <= max_participant_id; ++id) {
    ports.insert(rtps_metatraffic_unicast_port(domain, id));
    ports.insert(rtps_user_unicast_port(domain, id));
  }
  return ports;
}

ShmSweep remove_unused_shm_ports(const std::string& dir, double min_age_s, const std::set<int>& any_age) {
  ShmSweep r;
  std::map<int, std::vector<fs::path>> ports;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const int p = port_of(e.path().filename().string());
    if (p >= 0) ports[p].push_back(e.path());
  }
  if (ports.empty()) return r;
  std::set<std::string> mapped;
  r.unreadable_processes = mapped_paths(mapped);
  const std::string canon_dir = fs::weakly_canonical(dir, ec).string();
  const uid_t me = geteuid();
  const double now = static_cast<double>(std::time(nullptr));
  for (const auto& [port, files] : ports) {
    bool in_use = false, young = false, foreign = false;
    for (const auto& f : files) {
      if (mapped.count(f.string()) || mapped.count(canon_dir + "/" + f.filename().string())) in_use = true;
      if (f.filename().string().size() > 3 &&
          f.filename().string().compare(f.filename().string().size() - 3, 3, "_el") == 0 && flocked(f))
        in_use = true;
      struct stat st {};
      if (::lstat(f.c_str(), &st) != 0) continue;
      if (st.st_uid != me) foreign = true;
      if (!any_age.count(port) && now - static_cast<double>(st.st_mtime) < min_age_s) young = true;
    }
    if (in_use) {
      ++r.ports_in_use;
    } else if (young) {
      ++r.ports_too_young;
    } else if (!foreign) {
      for (const auto& f : files) fs::remove(f, ec);
      ++r.ports_removed;
    }
  }
  return r;
}

}  // namespace maptr::comm
