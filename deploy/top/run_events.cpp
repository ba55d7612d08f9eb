#include "deploy/top/run_events.hpp"

#include <algorithm>

namespace maptr::top {

namespace {
std::string tick_text(double at_s, double tick_hz) {
  return "tick " + std::to_string(config::first_tick_at(at_s, 1.0 / tick_hz));
}

/// "kill of L3", "fault open of L3", "fault torque=0.5 of L3".
std::string what(const std::string& action, const std::string& target, const std::string& mode, double value) {
  std::string a = action;
  if (action == "fault") {
    a += " " + mode;
    if (value != 0.0) a += "=" + model::param_value(value);
  }
  return a + " of " + target;
}

double number(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::nan("");
}
}  // namespace

std::map<long long, std::string> gate_faults(const config::Scenario& s) {
  std::map<long long, std::string> out;
  std::vector<config::FaultSpec> faults = s.faults;
  std::stable_sort(faults.begin(), faults.end(), [](const auto& a, const auto& b) { return a.at_s < b.at_s; });
  for (const auto& f : faults) {
    if (config::is_agent_fault_action(f.action)) continue;
    std::string& text = out[config::first_tick_at(f.at_s, s.dt())];
    text += (text.empty() ? "" : ", ") + what(f.action, f.target, f.mode, f.value);
  }
  return out;
}

std::vector<ViewEvent> recorded_events(const nlohmann::json& summary, double tick_hz) {
  std::vector<ViewEvent> out;
  for (const auto& f : summary.value("failures", nlohmann::json::array())) {
    if (f.contains("skipped")) continue;
    const std::string origin = f.value("origin", "scheduled");
    const double at = number(f, "at_s");
    const std::string w = what(f.value("action", ""), f.value("target", ""), f.value("mode", ""), f.value("value", 0.0));
    out.push_back({at, origin == "command" ? w + " (command)" : origin + " " + w + " (" + tick_text(at, tick_hz) + ")"});
  }
  for (const auto& e : summary.value("membership_events", nlohmann::json::array())) {
    std::string text = e.value("process", "?") + " " + e.value("kind", "?");
    if (e.contains("cause") && e["cause"].is_string()) text += " (" + e["cause"].get<std::string>() + ")";
    out.push_back({number(e, "t_s"), text});
  }
  const auto plant = summary.value("plant", nlohmann::json::object());
  const auto faults = plant.is_object() ? plant.value("agent_faults", nlohmann::json::object()) : nlohmann::json::object();
  for (const auto& d : faults.value("diagnoses", nlohmann::json::array())) {
    const std::string target = d.value("target", "?");
    out.push_back({number(d, "t_s"), d.value("event", "") == "isolated"
                                         ? target + " isolated by its group (" + d.value("diagnosed", "?") + ")"
                                         : target + " let back by its group"});
  }
  std::stable_sort(out.begin(), out.end(), [](const ViewEvent& a, const ViewEvent& b) { return a.t_s < b.t_s; });
  return out;
}

}  // namespace maptr::top
