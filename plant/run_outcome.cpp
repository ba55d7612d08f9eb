#include "plant/run_outcome.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace maptr::plant {

void TickTiming::add(float publish_us, float first_reply_us, float barrier_us, float integrate_us,
                     float tick_us, TickNote note) {
  publish_.push_back(publish_us);
  if (first_reply_us >= 0.0f) first_reply_.push_back(first_reply_us);
  barrier_.push_back(barrier_us);
  integrate_.push_back(integrate_us);
  tick_.push_back(tick_us);
  notes_.push_back(note);
}

nlohmann::json quantiles(std::vector<float> v) {
  if (v.empty()) return nlohmann::json::object();
  std::sort(v.begin(), v.end());
  auto q = [&](double p) { return v[static_cast<std::size_t>(p * (v.size() - 1))]; };
  double sum = 0.0;
  for (float x : v) sum += x;
  return nlohmann::json{{"median", q(0.5)}, {"mean", sum / static_cast<double>(v.size())},
                        {"p90", q(0.9)},    {"p99", q(0.99)},
                        {"max", v.back()},  {"n", v.size()}};
}

nlohmann::json TickTiming::slowest() const {
  if (tick_.empty()) return nlohmann::json::object();
  // The slowest 1 % by rank (at least one tick), ties broken by order: exactly that many ticks.
  std::vector<std::size_t> order(tick_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const std::size_t n_slow = std::max<std::size_t>(1, tick_.size() / 100);
  const std::size_t n_sorted = std::min(tick_.size(), std::max<std::size_t>(n_slow, 5));
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n_sorted), order.end(),
                    [&](std::size_t a, std::size_t b) { return tick_[a] > tick_[b] || (tick_[a] == tick_[b] && a < b); });
  std::vector<bool> slow_tick(tick_.size(), false);
  for (std::size_t i = 0; i < n_slow; ++i) slow_tick[order[i]] = true;
  const float threshold = tick_[order[n_slow - 1]];
  struct Count {
    double n = 0, agent = 0, group = 0, central = 0, none = 0, traced = 0, level2 = 0;
    void add(const TickNote& t) {
      ++n;
      (t.last == TickNote::kAgent ? agent : t.last == TickNote::kGroup ? group : t.last == TickNote::kCentral ? central : none) += 1;
      traced += t.traced;
      level2 += t.level2_solving;
    }
    nlohmann::json pct() const {
      const auto p = [&](double x) { return n > 0 ? 100.0 * x / n : 0.0; };
      return {{"last_agent_pct", p(agent)}, {"last_group_pct", p(group)}, {"last_central_pct", p(central)},
              {"last_none_pct", p(none)},   {"traced_pct", p(traced)},    {"level2_solving_pct", p(level2)}};
    }
  } slow, all;
  for (std::size_t i = 0; i < tick_.size(); ++i) {
    all.add(notes_[i]);
    if (slow_tick[i]) slow.add(notes_[i]);
  }
  return {{"threshold_us", threshold}, {"n", slow.n}, {"slowest", slow.pct()}, {"all", all.pct()},
          {"ticks", five_slowest(order)}};
}

nlohmann::json TickTiming::five_slowest(const std::vector<std::size_t>& order) const {
  constexpr std::size_t kListed = 5;
  nlohmann::json out = nlohmann::json::array();
  // publish_, barrier_ and integrate_ have one entry per tick_ (first_reply_ does not).
  for (std::size_t r = 0; r < std::min(kListed, order.size()); ++r) {
    const std::size_t i = order[r];
    const std::pair<const char*, float> parts[] = {
        {"publish", publish_[i]}, {"barrier", barrier_[i]}, {"integrate", integrate_[i]}};
    const auto* longest = &parts[0];
    for (const auto& p : parts)
      if (p.second > longest->second) longest = &p;
    out.push_back({{"tick", notes_[i].tick}, {"us", tick_[i]}, {"longest_part", longest->first},
                   {"longest_part_us", longest->second}});
  }
  return out;
}

nlohmann::json TickTiming::json() const {
  return {{"publish", quantiles(publish_)},     {"first_reply", quantiles(first_reply_)},
          {"barrier", quantiles(barrier_)},     {"integrate", quantiles(integrate_)},
          {"tick", quantiles(tick_)},           {"period", quantiles(period_)},
          {"slowest_1pct", slowest()}};
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
