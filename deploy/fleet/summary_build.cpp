#include "deploy/fleet/summary_build.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "control/level2/status.hpp"
#include "deploy/fleet/fault_analysis.hpp"
#include "deploy/fleet/membership_events.hpp"
#include "model/params.hpp"
#include "records/level2_log.hpp"
#include "records/run_files.hpp"

namespace maptr::deploy::fleet {

namespace {

/// The figures of one side's Level-2 decisions.
nlohmann::json level2_side(const std::vector<records::Level2Record>& log) {
  std::vector<double> ms;
  int checked = 0, differs = 0, infeasible = 0;
  for (const auto& d : log) {
    ms.push_back(d.solve_ms);
    const int status = static_cast<int>(d.status);
    if (status == control::kL2Infeasible) ++infeasible;
    if (status == control::kL2Ok && d.oracle_n_active >= 0) {
      ++checked;
      if (d.ipopt_n_active != d.oracle_n_active) ++differs;
    }
  }
  nlohmann::json s = {{"decisions", ms.size()},
                      {"infeasible", infeasible},
                      {"oracle_checked", checked},
                      {"oracle_differs", differs}};
  if (!ms.empty()) {
    std::sort(ms.begin(), ms.end());
    auto q = [&](double p) {
      return ms[std::min(ms.size() - 1, static_cast<std::size_t>(p * (ms.size() - 1) + 0.5))];
    };
    s["solve_ms_median"] = q(0.5);
    s["solve_ms_p95"] = q(0.95);
    s["solve_ms_max"] = ms.back();
  }
  return s;
}

std::string sha256_of(const std::string& path) {
  const std::string cmd = "sha256sum '" + path + "'";
  FILE* f = popen(cmd.c_str(), "r");
  if (!f) return "";
  char buf[128] = {0};
  std::string out;
  if (fgets(buf, sizeof(buf), f)) out = buf;
  pclose(f);
  return out.substr(0, out.find(' '));
}

/// The figures of the run from the plant's results, the launcher's last tick standing in.
void add_run_figures(nlohmann::json& s, const std::optional<records::PlantResults>& plant,
                     const RunRecord& r) {
  const PlantState& last = r.last_tick;
  // Without the plant's results, the launcher's last tick.
  records::PlantResults p;
  p.sim_time_s = last.t;
  p.energy_J = last.energy_J;
  p.active_agents = {last.active_L, last.active_R};
  if (plant) p = *plant;
  const nlohmann::json j = records::to_json(p);
  s["sim_time_s"] = p.sim_time_s;
  s["wall_time_s"] = r.run_wall_s;
  s["ticks"] = p.ticks;
  s["real_time_factor"] = p.sim_time_s / std::max(1e-9, r.run_wall_s);
  s["distance_m"] = p.distance_m;
  s["energy_J"] = p.energy_J;
  s["mileage_m_per_J"] = p.energy_J > 0 ? p.distance_m / p.energy_J : 0.0;
  s["mean_active_agents"] = p.mean_active_agents;
  s["active_agents"] = j["active_agents"];
  s["battery_discharge_mAh"] = j["battery_discharge_mAh"];
  s["path"] = plant ? j["path"] : nlohmann::json::object();
}

}  // namespace

std::string final_status(const std::string& launch_status, const std::optional<records::PlantResults>& plant,
                         const Child& pc) {
  if (launch_status != "ok") return launch_status;
  if (!plant)
    return "aborted: the plant ended without results (exit " + std::to_string(pc.exit_code) + ", signal " +
           std::to_string(pc.signal) + ")";
  return plant->status.empty() ? "unknown" : plant->status;
}

nlohmann::json level2_stats(const std::string& run_dir) {
  nlohmann::json out = nlohmann::json::object();
  for (int side = 0; side < 2; ++side) {
    const std::string path = records::level2_log_path(run_dir, side);
    if (!std::filesystem::exists(path)) continue;
    const char* name = side == 0 ? "L" : "R";
    // A broken log must not end the summary: the side is reported without decisions, with
    // the reader's error.
    try {
      out[name] = level2_side(records::read_level2_log(path));
    } catch (const records::RecordError& e) {
      out[name] = level2_side({});
      out[name]["error"] = e.what();
    }
  }
  return out;
}

std::string scenario_file(const std::string& source, const std::string& project_root) {
  const std::string root = project_root + "/";
  return source.rfind(root, 0) == 0 ? source.substr(root.size()) : source;
}

nlohmann::json processes_json(const std::vector<Child>& kids) {
  nlohmann::json procs = nlohmann::json::array();
  for (const auto& c : kids)
    procs.push_back({{"name", c.name},
                     {"pid", c.pid},
                     {"exit_code", c.exit_code},
                     {"signal", c.signal},
                     {"max_rss_kB", c.max_rss_kB},
                     {"starts", c.starts},
                     {"external", c.external}});
  for (std::size_t i = 0; i < kids.size(); ++i)
    if (kids[i].host >= 0) {
      procs[i]["host"] = config::host_name(kids[i].host);
      procs[i]["started_by"] = kids[i].prefix.empty() ? "" : kids[i].prefix.front();
      if (kids[i].remote_pid > 0) procs[i]["host_pid"] = kids[i].remote_pid;
    }
  return procs;
}

namespace {

/// The samples the fleet dropped: by process, the launcher's readiness, by kind.
void add_rejected(nlohmann::json& s, const std::optional<records::PlantResults>& plant, const RunRecord& r) {
  // Samples dropped as malformed, forged or from a wrong sender, by the process that dropped them;
  // the plant's late answers from their rightful sender are counted apart (plant.json late_samples).
  nlohmann::json rejected = plant ? nlohmann::json(plant->rejected_by_process) : nlohmann::json::object();
  rejected["launcher"] = r.launcher_rejected;
  s["rejected_samples"] = rejected;
  // The launcher's readiness: forged NodeReady samples, and stale ones from a process's earlier start.
  nlohmann::json ready = {{"forged", 0}, {"stale", 0}, {"malformed", 0}};
  for (const auto& [kind, n] : r.ready_rejected) ready[kind] = n;
  s["rejected_ready"] = ready;
  // By kind, for the processes that count their own by kind (the plant and the launcher).
  s["rejected_by_kind"] = {
      {"plant", plant ? nlohmann::json(plant->rejected_by_kind) : nlohmann::json::object()},
      {"launcher", r.launcher_by_kind}};
}

}  // namespace

nlohmann::json build_summary(const config::Scenario& sc, const std::string& project_root, const RunRecord& r,
                             const std::string& run_dir, const std::vector<Child>& kids) {
  const std::optional<records::PlantResults> plant = records::read_plant_results(run_dir);
  nlohmann::json s;
  s["scenario"] = sc.name;
  s["scenario_file"] = scenario_file(sc.source, project_root);
  s["agents"] = sc.robot.agents;
  s["mode"] = sc.mode;
  s["motor"] = sc.robot.motor.type;
  s["gross_mass_kg"] = sc.robot.gross_mass_kg;
  s["tick_hz"] = sc.tick_hz;
  add_run_figures(s, plant, r);
  s["discovery_s"] = r.discovery_s;
  s["discovery_server_restarts"] = r.discovery_restarts;
  s["discovery_rematched"] = r.rematched;
  s["transport"] = r.transport;
  s["agent_start"] = r.agent_start;
  nlohmann::json failures = r.failures;
  // The agents' own faults, which the plant applied and recorded, among the others in time order.
  for (const auto& f : plant ? plant->agent_faults.faults : std::vector<records::AgentFaultRecord>{}) {
    nlohmann::json e = f;
    e["action"] = "fault";
    e["at_s"] = f.injected_s;
    e["origin"] = "scheduled";
    e["energy_penalty_J"] = nullptr;  // against a fault-free twin: maptr experiment faults
    failures.push_back(e);
  }
  std::stable_sort(failures.begin(), failures.end(),
                   [](const nlohmann::json& a, const nlohmann::json& b) { return a.value("at_s", 0.0) < b.value("at_s", 0.0); });
  const std::vector<records::MembershipEvent> plant_events =
      plant ? plant->membership_events : std::vector<records::MembershipEvent>{};
  analyse_faults(failures, plant_events, records::trace_path(run_dir), sc.robot.wheel_radius_m);
  s["failures"] = failures;
  s["membership_events"] = membership_events(plant_events, r.failures);
  if (r.chaos_seed >= 0) s["chaos_seed"] = r.chaos_seed;
  s["plant"] = plant ? records::to_json(*plant) : nlohmann::json::object();
  add_rejected(s, plant, r);
  s["level2"] = level2_stats(run_dir);
  s["processes"] = processes_json(kids);
  if (!r.hosts.is_null()) s["hosts"] = r.hosts;
  if (!r.failovers.is_null()) s["failovers"] = r.failovers;
  s["recording"] = recording_check(r.recorded, plant);
  if (s["recording"].is_object()) s["recording"]["rejected"] = r.recorded_rejected;
  const std::string trace = records::trace_path(run_dir);
  s["trace_sha256"] = std::filesystem::exists(trace) ? sha256_of(trace) : "";
  s["status"] = recording_status(kids.empty() ? r.status : final_status(r.status, plant, kids.front()),
                                 s["recording"]);
  return s;
}

std::string recording_status(const std::string& status, const nlohmann::json& recording) {
  if (status != "ok" || !recording.is_object()) return status;
  std::string missing;
  const nlohmann::json incomplete = recording.value("incomplete", nlohmann::json::object());
  for (const auto& [topic, c] : incomplete.items())
    missing += (missing.empty() ? "" : ", ") + topic + " holds " + std::to_string(c.value("recorded", 0ULL)) +
               " of the " + std::to_string(c.value("taken_by_plant", 0ULL)) + " samples the plant used";
  return missing.empty() ? status : "degraded: run.mcap incomplete: " + missing;
}

nlohmann::json recording_check(const std::map<std::string, uint64_t>& recorded,
                               const std::optional<records::PlantResults>& plant) {
  if (recorded.empty()) return nullptr;
  nlohmann::json incomplete = nlohmann::json::object();
  for (const auto& [topic, taken] : plant ? plant->answers_taken : std::map<std::string, uint64_t>{}) {
    const auto it = recorded.find(topic);
    if (it == recorded.end()) continue;  // a topic run.mcap does not record
    if (it->second < taken) incomplete[topic] = {{"recorded", it->second}, {"taken_by_plant", taken}};
  }
  return {{"recorded", recorded}, {"incomplete", incomplete}};
}

}  // namespace maptr::deploy::fleet

namespace maptr::deploy {

namespace {
/// The console's line on a process's or a host's fault (kill, restart, pause, resume,
/// kill-host, partition, heal): when the plant saw it, when the speed came back, or why it was
/// skipped.
std::string process_fault_line(const nlohmann::json& f) {
  const auto num = [&f](const char* k) { return f.contains(k) && f[k].is_number() ? f[k].get<double>() : -1.0; };
  char buf[512];
  std::string what;
  if (f.contains("skipped")) {
    what = "skipped: " + f.value("skipped", std::string());
  } else {
    const bool back = f.value("action", "") == "restart" || f.value("action", "") == "resume" ||
                      f.value("action", "") == "heal";
    what = num("detected_s") >= 0.0
               ? std::string(back ? "answered again" : "seen by the plant") + " at " + model::param_value(num("detected_s")) + " s"
               : std::string(back ? "NEVER ANSWERED AGAIN" : "never seen by the plant");
    what += num("recovered_s") >= 0.0 ? ", speed back in band at " + model::param_value(num("recovered_s")) + " s"
                                      : ", speed out of band until the next fault or the end";
    std::snprintf(buf, sizeof(buf), "; max speed error %.2f %%", num("max_speed_error_pct"));
    what += buf;
  }
  std::snprintf(buf, sizeof(buf), "%-11s %s at %.2f s: %s\n", f.value("action", "").c_str(), f.value("target", "").c_str(),
                num("at_s"), what.c_str());
  return buf;
}

/// The console's lines on every fault of the run, in time order: what became of each, and the
/// false detections of the agents' own faults.
std::string fault_lines(const nlohmann::json& s) {
  std::ostringstream os;
  char buf[512];
  // The agents' own faults: what became of each.
  for (const auto& f : s.value("failures", nlohmann::json::array())) {
    if (f.value("action", "") != "fault") {
      os << process_fault_line(f);
      continue;
    }
    const auto num = [&f](const char* k) { return f.contains(k) && f[k].is_number() ? f[k].get<double>() : -1.0; };
    std::string mode = f.value("mode", "");
    if (f.value("value", 0.0) != 0.0) mode += "=" + model::param_value(f.value("value", 0.0));
    std::string what;
    if (num("detected_s") >= 0.0) {
      std::snprintf(buf, sizeof(buf), "detected %.2f s later as %s, isolated at %.2f s", num("detected_s") - num("injected_s"),
                    f.value("diagnosed_mode", std::string("?")).c_str(), num("isolated_s"));
      what = buf;
    } else {
      what = f.value("exposed_ticks", 0) > 0 ? "NOT DETECTED" : "not detected (it never acted on the drive)";
    }
    if (num("readmitted_s") >= 0.0) what += ", let back at " + model::param_value(num("readmitted_s")) + " s";
    if (const int n = f.value("relapses", 0); n > 0)
      what += ", flagged again " + (n == 1 ? std::string("once") : std::to_string(n) + " times");
    std::snprintf(buf, sizeof(buf), "fault       %s %s at %.2f s: %s; max speed error %.2f %%\n", f.value("target", "").c_str(),
                  mode.c_str(), num("injected_s"), what.c_str(), num("max_speed_error_pct"));
    os << buf;
  }
  const nlohmann::json plant_faults = s.contains("plant") && s["plant"].is_object()
                                          ? s["plant"].value("agent_faults", nlohmann::json::object())
                                          : nlohmann::json::object();
  if (plant_faults.value("false_detections", 0) > 0)
    os << "faults      " << plant_faults.value("false_detections", 0)
       << " healthy agents isolated (false detections): see plant.json agent_faults.diagnoses\n";
  return os.str();
}

/// The run in seven lines: status, scenario, times, energy, battery, processes, trace.
std::string run_lines(const nlohmann::json& s) {
  char buf[1024];
  long rss_max = 0;
  double rss_sum = 0;
  for (const auto& p : s["processes"]) {
    rss_max = std::max<long>(rss_max, p.value("max_rss_kB", 0L));
    rss_sum += p.value("max_rss_kB", 0L);
  }
  std::snprintf(buf, sizeof(buf),
                "status      %s\n"
                "scenario    %s: %d agents, motor %s, %.1f kg, mode %s\n"
                "simulated   %.1f s in %.2f s wall (real-time factor %.1f); discovery %.2f s\n"
                "distance    %.1f m, energy %.1f J, mileage %.4f m/J, mean active agents %.2f\n"
                "battery     discharge L %.1f mAh, R %.1f mAh\n"
                "processes   %zu, max RSS %.1f MB (mean %.1f MB)\n"
                "trace       sha256 %s\n",
                s.value("status", "").c_str(), s.value("scenario", "").c_str(), s.value("agents", 0),
                s.value("motor", "").c_str(), s.value("gross_mass_kg", 0.0), s.value("mode", "").c_str(),
                s.value("sim_time_s", 0.0), s.value("wall_time_s", 0.0), s.value("real_time_factor", 0.0),
                s.value("discovery_s", 0.0), s.value("distance_m", 0.0), s.value("energy_J", 0.0),
                s.value("mileage_m_per_J", 0.0), s.value("mean_active_agents", 0.0),
                s["battery_discharge_mAh"].value("L", 0.0), s["battery_discharge_mAh"].value("R", 0.0),
                s["processes"].size(), rss_max / 1024.0,
                s["processes"].empty() ? 0.0 : rss_sum / 1024.0 / s["processes"].size(),
                s.value("trace_sha256", "").c_str());
  return buf;
}

/// A line per side whose Level 2 decided: its count, Ipopt's time, the oracle, infeasibility.
std::string level2_lines(const nlohmann::json& s) {
  std::string out;
  char buf[512];
  if (s.contains("level2") && s["level2"].is_object())
    for (const auto& [side, l2] : s["level2"].items()) {
      if (l2.value("decisions", 0) == 0) continue;
      std::snprintf(buf, sizeof(buf), "level 2 %s   %d decisions, Ipopt median %.1f ms (max %.1f)%s%s\n",
                    side.c_str(), l2.value("decisions", 0), l2.value("solve_ms_median", 0.0),
                    l2.value("solve_ms_max", 0.0),
                    l2.value("oracle_checked", 0) > 0
                        ? (", oracle differed " + std::to_string(l2.value("oracle_differs", 0)) + " of " +
                           std::to_string(l2.value("oracle_checked", 0)))
                              .c_str()
                        : "",
                    l2.value("infeasible", 0) > 0
                        ? (", infeasible " + std::to_string(l2.value("infeasible", 0)) +
                           " times: the load needs more than the live agents give, all of them ran")
                              .c_str()
                        : "");
      out += buf;
    }
  return out;
}
}  // namespace

std::string human_summary(const nlohmann::json& s) {
  std::ostringstream os;
  char buf[512];
  os << run_lines(s);
  if (s.contains("path") && s["path"].is_object() && !s["path"].empty()) {
    const auto& p = s["path"];
    std::snprintf(buf, sizeof(buf),
                  "path        cross-track max %.3f m (t = %.2f s), rms %.3f m; heading error max %.3f rad; "
                  "final position error %.3f m\n",
                  p.value("cross_track_max_m", 0.0), p.value("cross_track_max_t_s", 0.0),
                  p.value("cross_track_rms_m", 0.0), p.value("heading_error_max_rad", 0.0),
                  p.value("final_position_error_m", 0.0));
    os << buf;
  }
  // The plant's lock-step thread without its real-time priority (no privilege): said once here.
  const std::string sched =
      s.contains("plant") && s["plant"].is_object() ? s["plant"].value("loop_scheduling", "") : "";
  if (sched.rfind("normal (", 0) == 0) os << "plant       lock-step thread " << sched << "\n";
  const nlohmann::json incomplete =
      s.contains("recording") && s["recording"].is_object()
          ? s["recording"].value("incomplete", nlohmann::json::object())
          : nlohmann::json::object();
  for (const auto& [topic, c] : incomplete.items()) {
    std::snprintf(buf, sizeof(buf), "recording   run.mcap INCOMPLETE: %s holds %llu messages, the plant used %llu\n",
                  topic.c_str(), static_cast<unsigned long long>(c.value("recorded", 0ull)),
                  static_cast<unsigned long long>(c.value("taken_by_plant", 0ull)));
    os << buf;
  }
  os << fault_lines(s);
  os << level2_lines(s);
  return os.str();
}

}  // namespace maptr::deploy
