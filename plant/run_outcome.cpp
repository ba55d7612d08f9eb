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

std::vector<std::string> fault_problems(const plant_core::FaultBook& book, long long exposed_ticks_needed) {
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

records::AgentFaults agent_faults(const plant_core::FaultBook& book) {
  records::AgentFaults out;
  for (const auto& r : book.records())
    out.faults.push_back(
        {r.target, r.mode, r.value, r.injected_s, r.detected_s, r.isolated_s,
         r.diagnosed_mode.empty() ? std::nullopt : std::optional<std::string>(r.diagnosed_mode), r.relapses,
         r.exposed_ticks, r.cleared_s, r.readmitted_s});
  for (const auto& e : book.events())
    out.diagnoses.push_back(
        {e.t_s, e.target, e.diagnosed.empty() ? "readmitted" : "isolated", e.diagnosed, e.false_detection});
  out.false_detections = book.false_detections();
  return out;
}

records::PlantResults plant_results(const plant_core::PlantCore& core, const ReportInputs& in,
                                    const std::vector<MembershipRecord>& records) {
  const auto& x = core.state();
  records::PlantResults j;
  j.status = in.status;
  j.end_reason = in.end_reason;
  j.sim_time_s = core.t();
  j.ticks = core.tick();
  j.tick_hz = in.tick_hz;
  j.loop_wall_s = in.loop_wall_s;
  j.distance_m = x[model::kDistance];
  j.energy_J = x[model::kEnergyL] + x[model::kEnergyR];
  j.energy_side_J = {x[model::kEnergyL], x[model::kEnergyR]};
  j.energy_ledger = {j.energy_J, 0.0, core.kinetic_energy_J(), x[model::kLossJoule],
                     x[model::kLossMech], x[model::kLossEmf]};
  j.mean_active_agents = core.mean_active_agents();
  j.active_agents = {core.last_active(0), core.last_active(1)};
  j.live_agents = {in.live_agents[0], in.live_agents[1]};
  j.battery_discharge_mAh = {core.drawn_mAh(0), core.drawn_mAh(1)};
  j.battery_state_mAh = {x[model::kChargeL], x[model::kChargeR]};
  j.agent_active_s = {core.active_time(0), core.active_time(1)};
  j.battery_V = {core.battery_V(0), core.battery_V(1)};
  j.pose = {x[model::kX], x[model::kY], x[model::kTheta]};
  j.final_speed_mps = x[model::kVx];
  const auto& tr = core.tracking();
  j.path = {tr.cross_track_max(), tr.cross_track_max_t(), tr.cross_track_rms(), tr.heading_error_max(),
            tr.final_position_error()};
  j.max_speed_error_pct = core.max_speed_error_pct();
  j.rms_speed_error_pct = core.rms_speed_error_pct();
  j.rejected_samples = in.rejected_samples;
  j.rejected_by_process = in.rejected_by_process;
  j.rejected_by_kind = in.rejected_by_kind;
  j.late_samples = in.late_samples;
  j.missed_deadlines = in.missed_deadlines;
  j.loop_scheduling = in.loop_scheduling;
  j.tick_repairs = in.tick_repairs;
  j.answers_taken = in.answers_taken;
  j.tick_timing_us = in.tick_timing_us;
  j.declared_dead_by_deadline = in.declared_dead_by_deadline;
  j.membership_events = records;
  j.group_wear = in.group_wear;
  j.agent_faults = agent_faults(core.faults());
  return j;
}

}  // namespace maptr::plant
