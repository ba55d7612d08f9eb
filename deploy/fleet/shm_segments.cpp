#include "deploy/fleet/shm_segments.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <ctime>
#include <filesystem>
#include <fstream>

namespace maptr::deploy::fleet {

namespace fs = std::filesystem;

namespace {
constexpr const char* kPrefix = "fastrtps_";
constexpr std::size_t kPrefixLen = 9;
constexpr std::size_t kIdLen = 16;  ///< characters of a segment's id
constexpr const char* kLockSuffix = "_el";

bool id_char(char c) { return std::isdigit(static_cast<unsigned char>(c)) || (c >= 'a' && c <= 'z'); }
}  // namespace

std::string segment_name(const std::string& file_name) {
  if (file_name.rfind(kPrefix, 0) != 0) return "";
  const std::string rest = file_name.substr(kPrefixLen);
  if (rest.size() != kIdLen && rest != rest.substr(0, kIdLen) + kLockSuffix) return "";
  for (std::size_t i = 0; i < kIdLen; ++i)
    if (!id_char(rest[i])) return "";
  if (rest.rfind("port", 0) == 0) return "";
  return file_name.substr(0, kPrefixLen + kIdLen);
}

std::string segment_in_maps_line(const std::string& line) {
  const auto slash = line.rfind('/');
  if (slash == std::string::npos) return "";
  std::string file = line.substr(slash + 1);
  if (const auto sp = file.find(' '); sp != std::string::npos) file.resize(sp);  // " (deleted)"
  return segment_name(file);
}

std::set<std::string> segments_mapped_by(int pid) {
  std::set<std::string> out;
  std::ifstream maps("/proc/" + std::to_string(pid) + "/maps");
  std::string line;
  while (std::getline(maps, line))
    if (line.find("/dev/shm/") != std::string::npos)
      if (auto s = segment_in_maps_line(line); !s.empty()) out.insert(s);
  return out;
}

bool segment_orphaned(const std::string& dir, const std::string& name) {
  const std::string el = dir + "/" + name + kLockSuffix;
  const int fd = ::open(el.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool held = ::flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);  // releases the lock if we took it
  return !held;
}

std::vector<std::string> remove_orphan_segments(const std::string& dir, double min_age_s,
                                                const std::set<std::string>& any_age) {
  std::vector<std::string> removed;
  std::error_code ec;
  const uid_t me = geteuid();
  const double now = static_cast<double>(std::time(nullptr));
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string file = e.path().filename().string();
    const std::string name = segment_name(file);
    if (name.empty()) continue;
    struct stat st {};
    if (::lstat(e.path().c_str(), &st) != 0 || st.st_uid != me) continue;
    if (file == name) {
      // A segment without lock file and still empty: its creator was killed between creating
      // and sizing it (nothing can map an empty segment). Otherwise one visit per segment: its
      // lock file.
      if (st.st_size == 0 && !fs::exists(fs::path(dir) / (name + kLockSuffix), ec) &&
          now - static_cast<double>(st.st_mtime) >= min_age_s && fs::remove(e.path(), ec))
        removed.push_back(name);
      continue;
    }
    if (!any_age.count(name) && now - static_cast<double>(st.st_mtime) < min_age_s) continue;
    if (!segment_orphaned(dir, name)) continue;
    fs::remove(fs::path(dir) / name, ec);
    fs::remove(e.path(), ec);
    removed.push_back(name);
  }
  return removed;
}

}  // namespace maptr::deploy::fleet
