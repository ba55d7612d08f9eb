// The rules of the agents' own faults (scenario actions fault and clear): which actions they
// are, when they act, and which mode takes which value.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

#include "config/scenario.hpp"

namespace maptr::config {

bool is_agent_fault_action(const std::string& a) { return a == "fault" || a == "clear"; }

long long first_tick_at(double at_s, double dt_s) {
  auto k = static_cast<long long>(std::ceil(at_s / dt_s));
  while (k > 0 && static_cast<double>(k - 1) * dt_s >= at_s) --k;
  while (static_cast<double>(k) * dt_s < at_s) ++k;
  return k;
}

std::string fault_mode_problem(const FaultSpec& f, const model::RobotParams& robot, std::string& field) {
  field = "mode";
  if (f.action != "fault") {
    if (!f.mode.empty()) return "only an action fault has a mode";
    field = "value";
    return f.value != 0.0 ? "only an action fault has a value" : "";
  }
  if (f.mode.empty())
    return "an action fault needs a mode: open, short, torque, resistance, stuck, sensor, erratic or liar";
  field = "value";
  const double v = f.value, rated = robot.motor.rated_voltage_V;
  if (!std::isfinite(v)) return "must be a finite number";
  if (f.mode == "open" || f.mode == "short" || f.mode == "liar")
    return v != 0.0 ? "mode " + f.mode + " takes no value" : "";
  if (f.mode == "torque")
    return v > 0.0 && v <= 1.0 ? "" : "torque=F scales the motor's torque constant: F in (0, 1]";
  if (f.mode == "resistance")
    return v >= 1.0 && v <= 100.0 ? "" : "resistance=F scales the winding's resistance: F in [1, 100]";
  if (f.mode == "stuck") {
    const double lo = robot.driver.bidirectional ? -rated : 0.0;
    return v >= lo && v <= rated ? ""
                                 : "stuck=V is a voltage the " + std::string(robot.driver.name()) +
                                       " driver can apply: V in [" + model::param_value(lo) + ", " +
                                       model::param_value(rated) + "]";
  }
  if (f.mode == "sensor")
    return v != 0.0 && std::fabs(v) <= 1000.0 ? "" : "sensor=B is a speed offset: B nonzero, |B| <= 1000 rad/s";
  if (f.mode == "erratic") return v > 0.0 && v <= 100.0 ? "" : "erratic=S is a noise level: S in (0, 100] V";
  field = "mode";
  return "unknown mode: one of open, short, torque, resistance, stuck, sensor, erratic, liar";
}

namespace {

std::string seconds(double t) {
  std::ostringstream os;
  os << t << " s";
  return os.str();
}

/// A process as the schedule leaves it: running, paused or dead, and since when.
struct ProcessState {
  enum Kind { kRunning, kPaused, kDead } kind = kRunning;
  double since = 0.0;
};

/// Why a process action contradicts the target's state ("" when it does not).
std::string process_problem(const FaultSpec& f, ProcessState& st) {
  const std::string& t = f.target;
  if (t == "plant" && f.action == "restart")
    return "the plant cannot be restarted: it holds the robot's state and the clock; a run whose plant dies ends aborted";
  if (t == "discovery" && f.action == "restart")
    return "the launcher restarts the discovery server by itself when it dies";
  const std::string dead = t + " is dead by then (killed at " + seconds(st.since) + ", no restart between)";
  const std::string paused = t + " is paused by then (paused at " + seconds(st.since) + ", no resume between)";
  if (f.action == "kill") {
    if (st.kind == ProcessState::kDead) return dead;
    // The launcher starts a killed discovery server again by itself.
    if (t != "discovery") st = {ProcessState::kDead, f.at_s};
  } else if (f.action == "restart") {
    if (st.kind == ProcessState::kRunning) return "a restart needs an earlier kill of " + t + " (it is running then)";
    if (st.kind == ProcessState::kPaused) return paused + ": resume it, or kill it before the restart";
    st = {ProcessState::kRunning, f.at_s};
  } else if (f.action == "pause") {
    if (st.kind == ProcessState::kDead) return dead;
    if (st.kind == ProcessState::kPaused) return paused;
    st = {ProcessState::kPaused, f.at_s};
  } else if (f.action == "resume") {
    if (st.kind != ProcessState::kPaused) return "a resume of " + t + " needs an earlier pause of it (not yet resumed)";
    st = {ProcessState::kRunning, f.at_s};
  }
  return "";
}

/// Why a host action contradicts the host's link ("" when it does not); `cut` holds the hosts
/// whose link is cut and since when.
std::string host_problem(const FaultSpec& f, std::map<std::string, double>& cut) {
  const auto it = cut.find(f.target);
  if (f.action == "heal") {
    if (it == cut.end()) return "a heal needs an earlier partition or kill-host of " + f.target + " (its link is up then)";
    cut.erase(it);
  } else {
    if (it != cut.end()) return f.target + "'s link is cut by then (since " + seconds(it->second) + ", no heal between)";
    cut[f.target] = f.at_s;
  }
  return "";
}

}  // namespace

std::optional<ScheduleProblem> schedule_problem(const std::vector<FaultSpec>& faults) {
  std::vector<std::size_t> order(faults.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return faults[a].at_s < faults[b].at_s; });
  std::map<std::string, ProcessState> process;
  std::map<std::string, double> cut;
  bool hosts_killed = false;
  const FaultSpec* plant_kill = nullptr;
  for (const std::size_t i : order) {
    const FaultSpec& f = faults[i];
    if (plant_kill)
      return ScheduleProblem{i, "at_s", "after the plant's kill at " + seconds(plant_kill->at_s) + " the run has ended: nothing after it happens"};
    std::string why;
    if (is_host_action(f.action)) {
      why = host_problem(f, cut);
      hosts_killed = hosts_killed || f.action == "kill-host";
    } else if (!is_agent_fault_action(f.action) && !hosts_killed) {
      why = process_problem(f, process[f.target]);
    }
    if (!why.empty()) return ScheduleProblem{i, f.action == "restart" && f.target == "plant" ? "target" : "action", why};
    if (f.target == "plant" && f.action == "kill") plant_kill = &f;
  }
  return std::nullopt;
}

}  // namespace maptr::config
