#include "deploy/fleet/ready_check.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "comm/posix/environment.hpp"

namespace maptr::deploy::fleet {

ReadyVerdict judge_ready(const ReadyClaim& c) {
  if (!c.well_formed) return ReadyVerdict::kMalformed;
  if (!c.known_name) return ReadyVerdict::kForged;
  if (c.from_earlier_participant && !c.from_current_participant) return ReadyVerdict::kStale;
  if (!c.from_current_participant) return ReadyVerdict::kForged;
  if (c.external) return c.external_pid_ok ? ReadyVerdict::kTaken : ReadyVerdict::kForged;
  return c.pid_matches ? ReadyVerdict::kTaken : ReadyVerdict::kForged;
}

std::vector<std::string> rematch_choice(const std::vector<std::string>& unready,
                                        const std::vector<std::string>& plant_unmatched,
                                        const std::set<std::string>& ready) {
  if (unready.size() == 1 && unready.front() == "plant" && !plant_unmatched.empty() &&
      std::all_of(plant_unmatched.begin(), plant_unmatched.end(),
                  [&ready](const std::string& n) { return ready.count(n) > 0; })) {
    std::set<std::string> seen;
    std::vector<std::string> out;
    for (const auto& n : plant_unmatched)
      if (seen.insert(n).second) out.push_back(n);
    return out;
  }
  std::vector<std::string> out = unready;
  if (out.size() > 1) out.erase(std::remove(out.begin(), out.end(), "plant"), out.end());
  return out;
}

const char* verdict_name(ReadyVerdict v) {
  switch (v) {
    case ReadyVerdict::kTaken:
      return "taken";
    case ReadyVerdict::kForged:
      return "forged";
    case ReadyVerdict::kStale:
      return "stale";
    case ReadyVerdict::kMalformed:
      return "malformed";
  }
  return "forged";
}

namespace {
/// The NUL-separated entries of /proc/PID/environ; nullopt if it cannot be read.
std::optional<std::vector<std::string>> environ_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  const std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return std::nullopt;
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= all.size(); ++i)
    if (i == all.size() || all[i] == '\0') {
      if (i > start) out.push_back(all.substr(start, i - start));
      start = i + 1;
    }
  return out;
}
}  // namespace

std::optional<std::string> external_pid_problem(pid_t pid, const std::string& binary, uint32_t fleet_id,
                                                int participant_id, bool& unreadable,
                                                const std::string& proc) {
  unreadable = false;
  if (pid <= 1) return "pid " + std::to_string(pid) + " is no process of the fleet";
  const std::string dir = proc + "/" + std::to_string(pid);
  std::error_code ec;
  if (!std::filesystem::exists(dir, ec)) return "no process " + std::to_string(pid);
  const auto exe = std::filesystem::read_symlink(dir + "/exe", ec);
  const auto env = environ_of(dir + "/environ");
  if (ec || !env) {
    unreadable = true;
    return "cannot read the executable or environment of pid " + std::to_string(pid);
  }
  const auto want = std::filesystem::weakly_canonical(binary, ec);
  if (exe != want && exe != std::filesystem::path(binary))
    return "pid " + std::to_string(pid) + " runs " + exe.string() + ", not " + binary;
  const std::string fid = std::string(comm::kEnvFleetId) + "=" + std::to_string(fleet_id);
  const std::string part = std::string(comm::kEnvParticipantId) + "=" + std::to_string(participant_id);
  bool has_fid = false, has_part = false;
  for (const auto& e : *env) {
    has_fid = has_fid || e == fid;
    has_part = has_part || e == part;
  }
  if (!has_fid || !has_part)
    return "pid " + std::to_string(pid) + " was not started with this fleet's " + (has_fid ? part : fid);
  return std::nullopt;
}

}  // namespace maptr::deploy::fleet
