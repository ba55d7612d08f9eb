#include "deploy/fleet/fault_schedule.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace maptr::deploy {

std::vector<config::FaultSpec> chaos_schedule(unsigned seed, const config::Scenario& s, int faults) {
  std::mt19937 rng(seed);
  std::vector<std::string> targets = {"group-L", "group-R", "central"};
  for (int side = 0; side < 2; ++side)
    for (int j = 0; j < s.robot.per_side(); ++j) targets.push_back(config::agent_name(side, j));
  // Faults start once the robot is moving and leave time to recover before the end.
  const double t0 = std::min(5.0, 0.2 * s.duration_s), t1 = std::max(t0, s.duration_s - 10.0);
  std::uniform_real_distribution<double> when(t0, t1), back(2.0, 8.0);
  std::uniform_int_distribution<std::size_t> who(0, targets.size() - 1);
  std::vector<config::FaultSpec> out;
  for (int i = 0; i < faults; ++i) {
    const std::string target = targets[who(rng)];
    const double at = std::round(when(rng) * 100.0) / 100.0;
    const double again = std::min(s.duration_s, std::round((at + back(rng)) * 100.0) / 100.0);
    // One outage per target: skip a target that is already scheduled to be down then.
    bool overlaps = false;
    for (std::size_t k = 0; k + 1 < out.size(); k += 2)
      if (out[k].target == target && at <= out[k + 1].at_s + 0.5 && again >= out[k].at_s - 0.5)
        overlaps = true;
    if (overlaps) continue;
    out.push_back({target, "kill", at});
    out.push_back({target, "restart", again});
  }
  // On several hosts, also one partition of a host other than h0 (the plant's by default), healed.
  if (s.hosts.count >= 2) {
    std::uniform_int_distribution<int> host(1, s.hosts.count - 1);
    const std::string h = config::host_name(host(rng));
    const double at = std::round(when(rng) * 100.0) / 100.0;
    out.push_back({h, "partition", at});
    out.push_back({h, "heal", std::min(s.duration_s, std::round((at + back(rng)) * 100.0) / 100.0)});
  }
  return out;
}

namespace fleet {

FaultAction decide_fault(const config::FaultSpec& f, const TargetState& s) {
  if (f.target == kDiscoveryTarget) {
    if (f.action == "kill" && s.running) return {FaultAction::kKill, ""};
    return {FaultAction::kSkip, "the discovery server is restarted by the launcher when it dies"};
  }
  if (s.known && s.external)
    return {FaultAction::kSkip, "an external process is not the launcher's to kill or start"};
  if (s.known && f.action == "kill" && s.running) return {FaultAction::kKill, ""};
  if (s.known && f.action == "restart" && !s.running) return {FaultAction::kRestart, ""};
  return {FaultAction::kSkip, "target not in a state for this action"};
}

FaultSchedule::FaultSchedule(std::vector<config::FaultSpec> faults) : faults_(std::move(faults)) {
  std::stable_sort(faults_.begin(), faults_.end(), [](auto& a, auto& b) { return a.at_s < b.at_s; });
}

std::vector<config::FaultSpec> FaultSchedule::due(double gate_t) {
  std::vector<config::FaultSpec> out;
  while (next_ < faults_.size() && gate_t >= faults_[next_].at_s) out.push_back(faults_[next_++]);
  return out;
}

void FaultSchedule::record(const config::FaultSpec& f, double at_s, double wall_ms, const FaultAction& a) {
  nlohmann::json rec = {{"target", f.target}, {"action", f.action}, {"at_s", at_s}, {"wall_ms", wall_ms}};
  if (a.kind == FaultAction::kSkip) rec["skipped"] = a.skipped;
  records_.push_back(rec);
}

void FaultSchedule::close() {
  for (; next_ < faults_.size(); ++next_)
    records_.push_back({{"target", faults_[next_].target},
                        {"action", faults_[next_].action},
                        {"at_s", faults_[next_].at_s},
                        {"skipped", "scheduled after the end of the run"}});
}

}  // namespace fleet
}  // namespace maptr::deploy
