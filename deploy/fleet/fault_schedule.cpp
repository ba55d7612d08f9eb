#include "deploy/fleet/fault_schedule.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace maptr::deploy {

namespace {
/// One target down from `from` to `to`, s.
struct Outage {
  std::string target;
  double from, to;
};
bool overlaps(const std::vector<Outage>& done, const std::string& target, double from, double to) {
  for (const auto& d : done)
    if (d.target == target && from <= d.to + 0.5 && to >= d.from - 0.5) return true;
  return false;
}

/// `n` agent faults of every mode, each on a random agent between t0 and t1 and cleared 2 to 8 s
/// later, from a random stream of their own (seeded from `seed`).
void add_agent_faults(unsigned seed, const config::Scenario& s, int n, double t0, double t1,
                      std::vector<config::FaultSpec>& out) {
  std::uniform_real_distribution<double> when(t0, t1), back(2.0, 8.0);
  std::mt19937 fault_rng(seed ^ 0x85ebca6bu);
  const double rated = s.robot.motor.rated_voltage_V;
  const std::pair<const char*, double> modes[] = {{"open", 0},       {"short", 0},         {"torque", 0.5},
                                                  {"resistance", 3}, {"stuck", rated / 2}, {"sensor", 5},
                                                  {"erratic", 2},    {"liar", 0}};
  std::uniform_int_distribution<int> agent(0, s.robot.agents - 1), mode(0, 7);
  for (int i = 0; i < n; ++i) {
    const int a = agent(fault_rng);
    const auto& [m, v] = modes[mode(fault_rng)];
    config::FaultSpec f = config::FaultSpec::of(
        config::agent_name(a / s.robot.per_side(), a % s.robot.per_side()), "fault", 0.0);
    f.mode = m;
    f.value = v;
    f.at_s = std::round(when(fault_rng) * 100.0) / 100.0;
    out.push_back(f);
    out.push_back(config::FaultSpec::of(
        f.target, "clear", std::min(s.duration_s, std::round((f.at_s + back(fault_rng)) * 100.0) / 100.0)));
  }
}
}  // namespace

std::vector<config::FaultSpec> chaos_schedule(unsigned seed, const config::Scenario& s,
                                              const ChaosOptions& o) {
  std::mt19937 rng(seed);
  // The kind of each outage comes from a stream of its own: targets and times stay those of
  // a schedule without pauses.
  std::mt19937 kind_rng(seed ^ 0x9e3779b9u);
  std::vector<std::string> targets = {"group-L", "group-R", "central"};
  for (int side = 0; side < 2; ++side)
    for (int j = 0; j < s.robot.per_side(); ++j) targets.push_back(config::agent_name(side, j));
  if (o.discovery) targets.push_back(fleet::kDiscoveryTarget);
  // Faults start once the robot is moving and leave time to recover before the end.
  const double t0 = std::min(5.0, 0.2 * s.duration_s), t1 = std::max(t0, s.duration_s - 10.0);
  std::uniform_real_distribution<double> when(t0, t1), back(2.0, 8.0), kind(0.0, 1.0);
  std::uniform_int_distribution<std::size_t> who(0, targets.size() - 1);
  std::vector<config::FaultSpec> out;
  std::vector<Outage> done;
  for (int i = 0; i < o.outages; ++i) {
    const std::string target = targets[who(rng)];
    const double at = std::round(when(rng) * 100.0) / 100.0;
    const double again = std::min(s.duration_s, std::round((at + back(rng)) * 100.0) / 100.0);
    // The discovery server is only killed: while it is paused no restarted process can be
    // found, and a fault gate would wait for one in vain.
    // Over ssh a pause cannot be done (Scenario::validate refuses it): kills only.
    const double pause_share = s.hosts.ssh ? 0.0 : o.pause_share;
    const bool pause = kind(kind_rng) < pause_share && target != fleet::kDiscoveryTarget;
    // One outage per target at a time.
    if (overlaps(done, target, at, again)) continue;
    done.push_back({target, at, again});
    if (pause) {
      out.push_back(config::FaultSpec::of(target, "pause", at));
      out.push_back(config::FaultSpec::of(target, "resume", again));
    } else {
      out.push_back(config::FaultSpec::of(target, "kill", at));
      // The launcher restarts a killed discovery server by itself.
      if (target != fleet::kDiscoveryTarget) out.push_back(config::FaultSpec::of(target, "restart", again));
    }
  }
  // On several hosts, also one partition of a host other than h0 (the plant's by default), healed.
  if (s.hosts.count >= 2) {
    std::uniform_int_distribution<int> host(1, s.hosts.count - 1);
    const std::string h = config::host_name(host(rng));
    const double at = std::round(when(rng) * 100.0) / 100.0;
    out.push_back(config::FaultSpec::of(h, "partition", at));
    out.push_back(config::FaultSpec::of(h, "heal", std::min(s.duration_s, std::round((at + back(rng)) * 100.0) / 100.0)));
  }
  add_agent_faults(seed, s, o.agent_faults, t0, t1, out);
  return out;
}

std::vector<config::FaultSpec> chaos_schedule(unsigned seed, const config::Scenario& s, int faults) {
  ChaosOptions o;
  o.outages = faults;
  return chaos_schedule(seed, s, o);
}

namespace fleet {

FaultAction decide_fault(const config::FaultSpec& f, const TargetState& s) {
  if (f.target == kDiscoveryTarget && f.action == "restart")
    return {FaultAction::kSkip, "the discovery server is restarted by the launcher when it dies"};
  if (s.known && s.external)
    return {FaultAction::kSkip, "an external process is not the launcher's to kill or start"};
  if (s.known && s.remote && (f.action == "pause" || f.action == "resume"))
    return {FaultAction::kSkip,
            "a process started over ssh runs on its machine: SIGSTOP would stop its ssh client, not it"};
  if (s.known && s.running) {
    if (f.action == "kill") return {FaultAction::kKill, ""};
    if (f.action == "pause" && !s.paused) return {FaultAction::kPause, ""};
    if (f.action == "resume" && s.paused) return {FaultAction::kResume, ""};
  }
  if (s.known && f.action == "restart" && !s.running) return {FaultAction::kRestart, ""};
  return {FaultAction::kSkip, "target not in a state for this action"};
}

std::vector<config::FaultSpec> launcher_faults(const std::vector<config::FaultSpec>& faults) {
  std::vector<config::FaultSpec> out;
  for (const auto& f : faults)
    if (!config::is_agent_fault_action(f.action)) out.push_back(f);
  return out;
}

FaultSchedule::FaultSchedule(std::vector<config::FaultSpec> faults) : faults_(std::move(faults)) {
  std::stable_sort(faults_.begin(), faults_.end(), [](auto& a, auto& b) { return a.at_s < b.at_s; });
}

std::vector<config::FaultSpec> FaultSchedule::due(double gate_t) {
  std::vector<config::FaultSpec> out;
  while (next_ < faults_.size() && gate_t >= faults_[next_].at_s) out.push_back(faults_[next_++]);
  return out;
}

void FaultSchedule::record(const config::FaultSpec& f, double at_s, double wall_ms, const FaultAction& a,
                           const std::string& origin) {
  nlohmann::json rec = {
      {"target", f.target}, {"action", f.action}, {"at_s", at_s}, {"wall_ms", wall_ms}, {"origin", origin}};
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
