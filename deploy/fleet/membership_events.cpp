#include "deploy/fleet/membership_events.hpp"

#include <map>
#include <set>
#include <vector>

namespace maptr::deploy {

namespace {
/// Simulated-time slack between a fault's gate and the plant's record of it, s.
constexpr double kTimeSlackS = 1e-6;

/// The fault action behind a launcher-driven kind ("" for the others).
std::string action_of(const std::string& kind) {
  static const std::map<std::string, std::string> m = {
      {"died", "kill"}, {"paused", "pause"}, {"resumed", "resume"}, {"started", "restart"}};
  const auto it = m.find(kind);
  return it == m.end() ? "" : it->second;
}

/// The latest applied fault of `action` on `process` at or before t_s not used yet; -1 if none.
int find_fault(const nlohmann::json& failures, const std::string& process, const std::string& action,
               double t_s, const std::set<int>& used) {
  int best = -1;
  for (std::size_t i = 0; i < failures.size(); ++i) {
    const auto& f = failures[i];
    if (f.contains("skipped") || f.value("target", "") != process || f.value("action", "") != action)
      continue;
    if (f.value("at_s", 0.0) > t_s + kTimeSlackS || used.count(static_cast<int>(i))) continue;
    best = static_cast<int>(i);
  }
  return best;
}
}  // namespace

std::string membership_kind(const std::string& e) {
  static const std::map<std::string, std::string> m = {{"died (launcher)", "died"},
                                                       {"lost (DDS liveliness)", "lease_lost"},
                                                       {"missed the tick deadline", "deadline_missed"},
                                                       {"paused (launcher)", "paused"},
                                                       {"resumed (launcher)", "resumed"},
                                                       {"started (launcher)", "started"},
                                                       {"rejoined", "rejoined"}};
  const auto it = m.find(e);
  return it == m.end() ? e : it->second;
}

nlohmann::json membership_events(const std::vector<records::MembershipEvent>& plant_events,
                                 const nlohmann::json& failures) {
  nlohmann::json out = nlohmann::json::array();
  std::set<int> used;
  std::map<std::string, std::pair<std::string, std::string>> last;  // process -> (kind, cause)
  for (const auto& e : plant_events) {
    const std::string& process = e.name;
    const std::string kind = membership_kind(e.event);
    const double t_s = e.t_s;
    nlohmann::json ev = {{"kind", kind}, {"process", process}, {"t_s", t_s}, {"wall_ms", e.wall_ms}};
    std::string cause;
    if (const std::string action = action_of(kind); !action.empty()) {
      const int i = find_fault(failures, process, action, t_s, used);
      if (i >= 0) used.insert(i);
      cause = i >= 0 ? failures[i].value("origin", "scheduled")
                     : (kind == "died" ? "external signal" : "launcher");
    } else if (kind == "lease_lost") {
      cause = "lease";
    } else if (kind == "deadline_missed") {
      cause = "deadline";
    } else if (kind == "rejoined" && last.count(process)) {
      ev["after"] = last[process].first;
      cause = last[process].second;
    } else {
      cause = "unknown";
    }
    ev["cause"] = cause;
    last[process] = {kind, cause};
    out.push_back(ev);
  }
  return out;
}

}  // namespace maptr::deploy
