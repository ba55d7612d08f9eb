#include "plant/run_outcome.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace maptr::plant {

void TickTiming::add(float publish_us, float first_reply_us, float barrier_us, float integrate_us,
                     float tick_us) {
  publish_.push_back(publish_us);
  if (first_reply_us >= 0.0f) first_reply_.push_back(first_reply_us);
  barrier_.push_back(barrier_us);
  integrate_.push_back(integrate_us);
  tick_.push_back(tick_us);
}

nlohmann::json quantiles(std::vector<float> v) {
  if (v.empty()) return nlohmann::json::object();
  std::sort(v.begin(), v.end());
  auto q = [&](double p) { return v[static_cast<std::size_t>(p * (v.size() - 1))]; };
  return nlohmann::json{{"median", q(0.5)}, {"p90", q(0.9)}, {"p99", q(0.99)}, {"n", v.size()}};
}

nlohmann::json TickTiming::json() const {
  return {{"publish", quantiles(publish_)},
          {"first_reply", quantiles(first_reply_)},
          {"barrier", quantiles(barrier_)},
          {"integrate", quantiles(integrate_)},
          {"tick", quantiles(tick_)}};
}

std::string run_status(const RunEnd& e, double degraded_band_pct) {
  if (e.stopped) return "aborted: stop signal";
  if (e.live_agents[0] == 0 || e.live_agents[1] == 0)
    return std::string("degraded: side ") + (e.live_agents[0] == 0 ? "L" : "R") +
           " has no live agent; the robot stopped";
  if (!e.silent_controllers.empty()) {
    std::string names;
    for (const auto& n : e.silent_controllers) names += (names.empty() ? "" : ", ") + n;
    return "degraded: " + names + " dead or paused at the end; " +
           (e.silent_controllers.size() == 1 ? "its" : "their") + " agents ran on their own safe behaviour";
  }
  if (!e.fault_problems.empty()) {
    std::string all;
    for (const auto& p : e.fault_problems) all += (all.empty() ? "" : "; ") + p;
    return "degraded: " + all;
  }
  if (e.path_tolerance_m > 0.0 && e.cross_track_max_m > e.path_tolerance_m) {
    char why[160];
    std::snprintf(why, sizeof(why),
                  "degraded: path not followed (max cross-track %.3f m at t = %.2f s > tolerance %.3g m)",
                  e.cross_track_max_m, e.cross_track_max_t_s, e.path_tolerance_m);
    return why;
  }
  if (e.reached_reference && !e.speed_lost) {  // a run too short to reach its speed is not degraded
    const double ref_v = e.ref_speed_mps;
    const double err = ref_v > 0.0 ? 100.0 * std::fabs(e.speed_mps - ref_v) / ref_v : 0.0;
    if (err > degraded_band_pct)
      return "degraded: the robot ended " + std::to_string(err) + "% off its reference speed";
  }
  return "ok";
}

bool aborted(const std::string& status) { return status.rfind("aborted", 0) == 0; }

std::string end_reason(bool speed_lost, double stop_below_speed_pct, double hold_s, double t_s) {
  if (!speed_lost) return "duration reached";
  std::ostringstream hold;
  hold << hold_s;
  return "the speed stayed more than " + std::to_string(stop_below_speed_pct) + "% below its reference for " +
         hold.str() + " s at t=" + std::to_string(t_s) + " s";
}

std::vector<std::string> fault_problems(const sim::FaultBook& book, long long exposed_ticks_needed) {
  std::vector<std::string> out;
  char line[200];
  for (const auto& r : book.records()) {
    if (r.detected_s || r.exposed_ticks <= exposed_ticks_needed) continue;
    std::snprintf(line, sizeof(line), "fault %s%s on %s at %.2f s not detected", r.mode.c_str(),
                  r.value != 0.0 ? ("=" + model::param_value(r.value)).c_str() : "", r.target.c_str(), r.injected_s);
    out.push_back(line);
  }
  for (const auto& e : book.events())
    if (e.false_detection) {
      std::snprintf(line, sizeof(line), "%s isolated at %.2f s as %s with no fault in force (a false detection)",
                    e.target.c_str(), e.t_s, e.diagnosed.c_str());
      out.push_back(line);
    }
  return out;
}

nlohmann::json agent_faults_json(const sim::FaultBook& book) {
  auto opt = [](const std::optional<double>& v) -> nlohmann::json { return v ? nlohmann::json(*v) : nlohmann::json(); };
  nlohmann::json faults = nlohmann::json::array();
  for (const auto& r : book.records())
    faults.push_back({{"target", r.target},
                      {"mode", r.mode},
                      {"value", r.value},
                      {"injected_s", r.injected_s},
                      {"detected_s", opt(r.detected_s)},
                      {"isolated_s", opt(r.isolated_s)},
                      {"diagnosed_mode", r.diagnosed_mode.empty() ? nlohmann::json() : nlohmann::json(r.diagnosed_mode)},
                      {"relapses", r.relapses},
                      {"exposed_ticks", r.exposed_ticks},
                      {"cleared_s", opt(r.cleared_s)},
                      {"readmitted_s", opt(r.readmitted_s)}});
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : book.events())
    events.push_back({{"t_s", e.t_s},
                      {"target", e.target},
                      {"event", e.diagnosed.empty() ? "readmitted" : "isolated"},
                      {"diagnosed", e.diagnosed},
                      {"false_detection", e.false_detection}});
  return {{"faults", faults}, {"diagnoses", events}, {"false_detections", book.false_detections()}};
}

nlohmann::json membership_json(const std::vector<MembershipRecord>& records) {
  nlohmann::json events = nlohmann::json::array();
  for (const auto& r : records)
    events.push_back({{"name", r.name}, {"event", r.event}, {"t_s", r.t_s}, {"wall_ms", r.wall_ms}});
  return events;
}

nlohmann::json plant_report(const sim::PlantCore& core, const ReportInputs& in,
                            const std::vector<MembershipRecord>& records) {
  const auto& x = core.state();
  nlohmann::json j;
  j["status"] = in.status;
  j["sim_time_s"] = core.t();
  j["ticks"] = core.tick();
  j["tick_hz"] = in.tick_hz;
  j["loop_wall_s"] = in.loop_wall_s;
  j["distance_m"] = x[model::kDistance];
  j["energy_J"] = x[model::kEnergyL] + x[model::kEnergyR];
  j["energy_side_J"] = {{"L", x[model::kEnergyL]}, {"R", x[model::kEnergyR]}};
  j["mean_active_agents"] = core.mean_active_agents();
  j["active_agents"] = {{"L", core.last_active(0)}, {"R", core.last_active(1)}};
  j["live_agents"] = {{"L", in.live_agents[0]}, {"R", in.live_agents[1]}};
  j["battery_discharge_mAh"] = {{"L", core.drawn_mAh(0)}, {"R", core.drawn_mAh(1)}};
  j["battery_state_mAh"] = {{"L", x[model::kChargeL]}, {"R", x[model::kChargeR]}};
  j["agent_active_s"] = {{"L", core.active_time(0)}, {"R", core.active_time(1)}};
  j["end_reason"] = in.end_reason;
  j["battery_V"] = {{"L", core.battery_V(0)}, {"R", core.battery_V(1)}};
  j["pose"] = {{"x_m", x[model::kX]}, {"y_m", x[model::kY]}, {"theta_rad", x[model::kTheta]}};
  j["final_speed_mps"] = x[model::kVx];
  const auto& tr = core.tracking();
  j["path"] = {{"cross_track_max_m", tr.cross_track_max()},
               {"cross_track_max_t_s", tr.cross_track_max_t()},
               {"cross_track_rms_m", tr.cross_track_rms()},
               {"heading_error_max_rad", tr.heading_error_max()},
               {"final_position_error_m", tr.final_position_error()}};
  j["max_speed_error_pct"] = core.max_speed_error_pct();
  j["rms_speed_error_pct"] = core.rms_speed_error_pct();
  j["rejected_samples"] = in.rejected_samples;
  j["rejected_by_process"] = in.rejected_by_process;
  j["rejected_by_kind"] = in.rejected_by_kind;
  j["late_samples"] = in.late_samples;
  j["missed_deadlines"] = in.missed_deadlines;
  j["loop_scheduling"] = in.loop_scheduling;
  j["tick_repairs"] = in.tick_repairs;
  j["answers_taken"] = in.answers_taken;
  j["tick_timing_us"] = in.tick_timing_us;
  j["declared_dead_by_deadline"] = in.declared_dead_by_deadline;
  j["membership_events"] = membership_json(records);
  j["group_wear"] = in.group_wear;
  j["agent_faults"] = agent_faults_json(core.faults());
  return j;
}

}  // namespace maptr::plant
