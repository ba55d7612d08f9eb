#include "deploy/fleet/registry.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "comm/posix/environment.hpp"
#include "deploy/fleet/control_fifo.hpp"
#include "records/run_files.hpp"

namespace maptr::deploy::fleet {

namespace fs = std::filesystem;

std::string registry_dir(const char* xdg_runtime_dir, unsigned uid) {
  if (xdg_runtime_dir && xdg_runtime_dir[0] == '/') return std::string(xdg_runtime_dir) + "/maptr/fleets";
  if (uid == 0) return "/run/maptr/fleets";
  return "/tmp/maptr-" + std::to_string(uid) + "/fleets";
}

std::string registry_dir() { return registry_dir(std::getenv(comm::kEnvRuntimeDir), getuid()); }

long long process_start_ticks(int pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  if (!std::getline(in, text)) return -1;
  // The name (field 2) is in parentheses and may hold spaces: count the fields after its ')'.
  const auto close = text.rfind(')');
  if (close == std::string::npos) return -1;
  std::istringstream rest(text.substr(close + 2));
  std::string field;
  for (int i = 3; i <= 22 && rest >> field; ++i)
    if (i == 22) return std::atoll(field.c_str());
  return -1;
}

FleetRegistration::FleetRegistration(const std::string& run_dir, const std::string& scenario, int domain) {
  const std::string dir = registry_dir();
  std::error_code ec;
  fs::create_directories(dir, ec);
  // Only its user reads and writes the folder (the parents made here too, for /tmp).
  struct stat st {};
  if (!ec && ::stat(fs::path(dir).parent_path().c_str(), &st) == 0 && st.st_uid == getuid())
    ::chmod(fs::path(dir).parent_path().c_str(), 0700);
  else
    return;  // no registry folder of this user's: the fleet runs unregistered (found under runs/)
  FleetEntry e;
  e.run_dir = fs::absolute(run_dir, ec).lexically_normal().string();
  e.scenario = scenario;
  e.pid = static_cast<int>(getpid());
  e.start_ticks = process_start_ticks(e.pid);
  e.domain = domain;
  e.started_unix_s = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  path_ = dir + "/" + std::to_string(e.pid) + ".json";
  (void)running_fleets();  // drops the entries of launchers killed before they could remove theirs
  if (!records::write_registry_entry(path_, e))
    path_.clear();  // no registry here: the fleet runs unregistered (found under runs/)
}

FleetRegistration::~FleetRegistration() {
  std::error_code ec;
  if (!path_.empty()) fs::remove(path_, ec);
}

std::vector<FleetEntry> running_fleets() {
  std::vector<FleetEntry> out;
  std::error_code ec;
  for (const auto& f : fs::directory_iterator(registry_dir(), ec)) {
    if (f.path().extension() != ".json") continue;
    const auto e = records::read_registry_entry(f.path().string());
    if (!e) continue;
    const bool launcher_runs = process_start_ticks(e->pid) == e->start_ticks;
    if (!launcher_runs) {
      fs::remove(f.path(), ec);  // its launcher is gone (killed before it could say so)
      continue;
    }
    if (fs::is_fifo(control_fifo_path(e->run_dir), ec)) out.push_back(*e);
  }
  std::sort(out.begin(), out.end(), [](const FleetEntry& a, const FleetEntry& b) { return a.started_unix_s > b.started_unix_s; });
  return out;
}

double trace_time_s(const std::string& run_dir) {
  std::ifstream in(records::trace_path(run_dir), std::ios::binary);
  if (!in) return std::nan("");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  const std::streamoff from = std::max<std::streamoff>(0, size - 8192);
  in.seekg(from);
  std::string tail((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The last complete row: the one before the final newline (a row being written is cut).
  const auto end = tail.rfind('\n');
  if (end == std::string::npos) return std::nan("");
  const auto begin = tail.rfind('\n', end == 0 ? 0 : end - 1);
  const std::string row = tail.substr(begin == std::string::npos ? 0 : begin + 1, end - (begin == std::string::npos ? 0 : begin + 1));
  const auto comma = row.find(',');
  if (comma == std::string::npos) return std::nan("");
  char* stop = nullptr;
  const std::string t = row.substr(comma + 1, row.find(',', comma + 1) - comma - 1);
  const double v = std::strtod(t.c_str(), &stop);
  return stop != t.c_str() && *stop == '\0' ? v : std::nan("");
}

}  // namespace maptr::deploy::fleet
