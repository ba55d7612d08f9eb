#include "deploy/cli/soak_leftovers.hpp"

#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include "comm/posix/environment.hpp"
#include "comm/posix/shm_files.hpp"
#include "deploy/fleet/shm_segments.hpp"
#include "deploy/fleet/summary_build.hpp"
#include "records/fleet_file.hpp"
#include "records/run_files.hpp"

namespace maptr::deploy::cli {

namespace fs = std::filesystem;

namespace {
/// Wall time a fleet's processes get to be gone after its launcher ended, s.
constexpr double kLeftoverGraceS = 3.0;
constexpr std::chrono::milliseconds kPoll{100};
constexpr const char* kShmDir = "/dev/shm";
/// Ports of one DDS domain (the RTPS domain gain): a fleet of up to about 120 participant ids,
/// restarts included, stays within them.
constexpr int kDomainPorts = 250;

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

void sample_segments(pid_t launcher, const std::string& dir, std::set<std::string>& out) {
  std::vector<pid_t> pids = {launcher};
  if (const auto fleet = records::read_fleet_file(dir))
    for (pid_t p : pids_of_fleet(std::to_string(fleet->fleet_id))) pids.push_back(p);
  for (pid_t p : pids)
    for (const auto& s : fleet::segments_mapped_by(p)) out.insert(s);
}

std::vector<pid_t> pids_of_fleet(const std::string& fleet_id) {
  const std::string needle = std::string(comm::kEnvFleetId) + "=" + fleet_id;
  std::vector<pid_t> out;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(e.path() / "environ", std::ios::binary);
    std::string env((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (std::size_t p = 0; (p = env.find(needle, p)) != std::string::npos; p += needle.size())
      if ((p == 0 || env[p - 1] == '\0') &&
          (p + needle.size() == env.size() || env[p + needle.size()] == '\0'))
        out.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return out;
}

std::string check_leftovers(const std::string& run_dir) {
  const auto fleet = records::read_fleet_file(run_dir);
  if (!fleet) return "";  // the fleet never started
  const std::string id = std::to_string(fleet->fleet_id);
  const auto t0 = Clock::now();
  std::vector<pid_t> left = pids_of_fleet(id);
  while (!left.empty() && since(t0) < kLeftoverGraceS) {
    std::this_thread::sleep_for(kPoll);
    left = pids_of_fleet(id);
  }
  if (left.empty()) return "";
  std::string pids;
  for (pid_t p : left) {
    pids += " " + std::to_string(p);
    kill(p, SIGKILL);
  }
  // Gone for good before the shared-memory checks (a dead owner's locks are free).
  for (const auto t1 = Clock::now(); !pids_of_fleet(id).empty() && since(t1) < kLeftoverGraceS;)
    std::this_thread::sleep_for(kPoll);
  return std::to_string(left.size()) + " process(es) of the fleet left:" + pids;
}

ShmCount count_shm(int domain) {
  ShmCount c;
  const int base = comm::rtps_domain_port_base(domain);
  for (const auto& e : fs::directory_iterator(kShmDir)) {
    const std::string n = e.path().filename();
    const std::string port = n.rfind("sem.", 0) == 0 ? n.substr(4) : n;
    if (port.rfind("fastrtps_port", 0) == 0) {
      const int p = std::atoi(port.c_str() + 13);
      if (p >= base && p < base + kDomainPorts) ++c.ports;
    }
  }
  return c;
}

std::string check_shm(const ShmCount& before, const ShmCount& after) {
  if (after.ports <= before.ports) return "";
  return "/dev/shm grew: domain port files " + std::to_string(before.ports) + " -> " +
         std::to_string(after.ports);
}

std::string check_segments(const std::set<std::string>& own) {
  std::vector<std::string> left;
  for (const auto& s : own)
    if (fleet::segment_orphaned(kShmDir, s)) left.push_back(s);
  if (left.empty()) return "";
  std::string names;
  for (const auto& s : left) {
    names += " " + s;
    std::error_code ec;
    fs::remove(fs::path(kShmDir) / s, ec);
    fs::remove(fs::path(kShmDir) / (s + "_el"), ec);
  }
  return std::to_string(left.size()) +
         " shared-memory segment(s) of the fleet left without owner (removed):" + names;
}

}  // namespace maptr::deploy::cli
