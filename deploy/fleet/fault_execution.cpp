#include "deploy/fleet/fault_execution.hpp"

#include <cstdio>

namespace maptr::deploy::fleet {

namespace {
std::string said(const char* what, const std::string& who, pid_t pid, double at_s) {
  char t[32];
  std::snprintf(t, sizeof t, "%.2f", at_s);
  return std::string("fault: ") + what + " " + who + " (pid " + std::to_string(pid) + ") at t=" + t + " s";
}
}  // namespace

FaultOutcome FaultExecution::apply(const config::FaultSpec& f, double at_s, double wall_ms,
                                   const std::string& origin) {
  FaultOutcome o{decide_fault(f, targets_.state_of(f.target)), ""};
  const std::string who = f.target == kDiscoveryTarget ? std::string("the discovery server") : f.target;
  const pid_t before = targets_.pid_of(f.target);
  switch (o.action.kind) {
    case FaultAction::kKill:
      targets_.kill_target(f.target);
      o.line = said("killed", who, before, at_s);
      break;
    case FaultAction::kRestart:
      targets_.restart_target(f.target);
      o.line = said("restarted", who, targets_.pid_of(f.target), at_s);
      break;
    case FaultAction::kPause:
    case FaultAction::kResume:
      targets_.pause_target(f.target, o.action.kind == FaultAction::kPause);
      o.line = said(o.action.kind == FaultAction::kPause ? "paused" : "resumed", who, before, at_s);
      break;
    case FaultAction::kSkip:
      break;
  }
  schedule_.record(f, at_s, wall_ms, o.action, origin);
  return o;
}

}  // namespace maptr::deploy::fleet
