#include "deploy/studies/bench/memory.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "records/fleet_file.hpp"
#include "records/run_files.hpp"

namespace maptr::deploy {

namespace fs = std::filesystem;

namespace {
/// trace.csv this long: about 2 s simulated, past discovery and warm-up.
constexpr std::uintmax_t kTraceBytesUnderWay = 6000;
constexpr auto kGiveUpAfter = std::chrono::minutes(30);
constexpr auto kPoll = std::chrono::milliseconds(200);

/// Proportional set size of a process, kB; -1 when it cannot be read.
long pss_kB(long pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/smaps_rollup");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("Pss:", 0) == 0) return std::stol(line.substr(4));
  return -1;
}

/// Waits for the lock-step to run for a while; false when the run ended or never got there.
bool wait_under_way(const std::string& run_dir, const std::atomic<bool>& done) {
  const auto t0 = std::chrono::steady_clock::now();
  while (!done.load()) {
    std::error_code ec;
    const std::string trace = records::trace_path(run_dir);
    if (fs::exists(trace, ec) && fs::file_size(trace, ec) > kTraceBytesUnderWay) return true;
    if (std::chrono::steady_clock::now() - t0 > kGiveUpAfter) return false;
    std::this_thread::sleep_for(kPoll);
  }
  return false;
}
}  // namespace

FleetMemory sample_memory(const std::string& run_dir, const std::atomic<bool>& done) {
  FleetMemory m;
  if (!wait_under_way(run_dir, done)) return m;
  const auto fleet = records::read_fleet_file(run_dir);
  if (!fleet) return m;
  for (const auto& p : fleet->processes) {
    const long kb = pss_kB(p.host_pid.value_or(p.pid));  // over ssh the process, not its ssh client
    if (kb < 0) continue;
    m.total_pss_kB += kb;
    if (p.name[0] == 'L' || p.name[0] == 'R') m.agent_pss_kB.push_back(kb);
  }
  const long launcher = pss_kB(fleet->launcher_pid);
  if (launcher > 0) m.total_pss_kB += launcher;
  return m;
}

double cpu_seconds(int who) {
  rusage ru{};
  getrusage(who, &ru);
  return ru.ru_utime.tv_sec + ru.ru_utime.tv_usec * 1e-6 + ru.ru_stime.tv_sec + ru.ru_stime.tv_usec * 1e-6;
}

double median(std::vector<long> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace maptr::deploy
