#include "records/summary_fields.hpp"

#include <algorithm>

namespace maptr::records {

namespace {

/// "a[][]" -> "a", with the number of "[]" it ended with.
std::string base_of(const std::string& segment, int& lists) {
  std::string s = segment;
  lists = 0;
  while (s.size() >= 2 && s.compare(s.size() - 2, 2, "[]") == 0) {
    s.resize(s.size() - 2);
    ++lists;
  }
  return s;
}

std::vector<std::string> segments(const std::string& path) {
  std::vector<std::string> out;
  std::string::size_type from = 0;
  for (;;) {
    const auto dot = path.find('.', from);
    out.push_back(path.substr(from, dot == std::string::npos ? std::string::npos : dot - from));
    if (dot == std::string::npos) return out;
    from = dot + 1;
  }
}

bool segment_matches(const std::string& pattern, const std::string& segment) {
  int p_lists = 0, s_lists = 0;
  const std::string p = base_of(pattern, p_lists), s = base_of(segment, s_lists);
  if (p_lists != s_lists) return false;
  if (p.size() >= 2 && p.front() == '<' && p.back() == '>') return !s.empty();
  return p == s;
}

}  // namespace

bool summary_path_matches(const std::string& pattern, const std::string& path) {
  const std::vector<std::string> p = segments(pattern), s = segments(path);
  if (p.size() != s.size()) return false;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!segment_matches(p[i], s[i])) return false;
  return true;
}

namespace {

/// The run as a whole (deploy/fleet/summary_build.cpp).
std::vector<SummaryField> run_keys() {
  return {
      {"status", "text", "",
       "How the run ended: ok, degraded: <why> or aborted: <why>; the launcher's status if it aborted the run, else the plant's"},
      {"scenario", "text", "",
       "The scenario's name (its `name` field, which also names the run folder); the scenario as run is the folder's scenario.yaml"},
      {"scenario_file", "text", "", "The scenario file the run started from: its path inside the project, or as given when outside it"},
      {"agents", "integer", "1", "Number of wheel-motor agents N, both sides together (robot.agents)"},
      {"mode", "text", "", "all (every agent drives) or ec (energy-conscious: Levels 2 and 3 choose the agents)"},
      {"motor", "text", "", "Motor type of the paper's Table 1: I or II"},
      {"gross_mass_kg", "number", "kg", "Gross mass of the robot: payload, chassis, motors and wheels (robot.gross_mass_kg)"},
      {"tick_hz", "number", "Hz", "Ticks of the lock-step per simulated second (tick_hz)"},
      {"sim_time_s", "number", "s",
       "Simulated time reached: the plant's, or the last tick the launcher saw when the plant left no results"},
      {"wall_time_s", "number", "s",
       "Wall time from the start of the run (after discovery) until the plant ended or the launcher aborted the run"},
      {"ticks", "integer", "1", "Ticks the plant integrated; 0 when the plant left no results"},
      {"real_time_factor", "number", "1", "sim_time_s / wall_time_s: simulated seconds per second of wall time"},
      {"distance_m", "number", "m", "Distance the robot travelled (integral of |v_x|), from the plant; 0 when the plant left no results"},
      {"energy_J", "number", "J",
       "Energy drawn from both batteries: the plant's figure, or the last tick the launcher saw when the plant left no results"},
      {"mileage_m_per_J", "number", "m/J", "distance_m / energy_J from the plant's results; 0 when no energy was drawn or the plant left none"},
      {"mean_active_agents", "number", "1", "Mean number of agents driving per tick over the run, both sides together"},
      {"active_agents.<side>", "integer", "1",
       "Agents of side L or R driving in the last tick: the plant's figure, or the last tick the launcher saw"},
      {"battery_discharge_mAh.<side>", "number", "mAh",
       "Charge drawn from side L's or R's battery during the run, without the initial discharge; 0 when the plant left no results"},
      {"discovery_s", "number", "s", "Wall time from the launch until every process reported ready (or until the launcher gave up)"},
      {"discovery_server_restarts", "integer", "1",
       "Times the launcher started a discovery server again after it died (every host's server together)"},
      {"discovery_rematched[]", "text", "",
       "A process started again before the run began (not ready in time, dead during discovery, or unseen by the recorder)"},
      {"transport", "text", "", "DDS data transport: shm, udp, or shm+udp (on several hosts or a secure domain)"},
      {"agent_start", "text", "", "How the launcher started the agents: zygote (forked from a zygote process) or exec"},
      {"chaos_seed", "integer", "1", "The seed of --chaos, whose random faults the run had; present only with --chaos"},
      {"trace_sha256", "text", "", "SHA-256 of trace.csv, in hex; empty when the run has no trace.csv"}
  };
}

/// The robot against its path: plant.path, copied ({} when the plant left no results).
std::vector<SummaryField> path_keys() {
  return {
      {"path.cross_track_max_m", "number", "m", "Largest |cross-track error| from the reference path after the first second"},
      {"path.cross_track_max_t_s", "number", "s", "Simulated time of the largest cross-track error"},
      {"path.cross_track_rms_m", "number", "m", "RMS cross-track error after the first second"},
      {"path.heading_error_max_rad", "number", "rad", "Largest |heading error| after the first second, while the reference moves"},
      {"path.final_position_error_m", "number", "m", "Distance from the robot's last pose to the reference's last pose"}
  };
}

/// Every fault, in time order: the launcher's (processes, hosts) and the agents' own (from plant.json).
std::vector<SummaryField> failure_keys() {
  return {
      {"failures[].target", "text", "",
       "What the fault acts on: an agent, group-L, group-R, central, plant, discovery (the server) or a host (h0, h1, ...)"},
      {"failures[].action", "text", "",
       "kill, restart, pause, resume, kill-host, partition or heal (applied by the launcher), or fault (an agent's own, from the plant)"},
      {"failures[].at_s", "number", "s",
       "Simulated time it was applied (its fault gate, or the time of a command); due after the end: its scheduled time; agents' faults: injected_s"},
      {"failures[].wall_ms", "number", "ms",
       "Wall clock when the launcher applied it, ms since the epoch; absent for agents' faults and faults due after the run's end"},
      {"failures[].origin", "text", "",
       "scheduled (scenario, --kill ...), chaos (--chaos) or command (maptr kill ...); host and agent faults always scheduled; absent if due after the end"},
      {"failures[].skipped", "text", "",
       "Why the launcher did not apply it (e.g. target not in a state for this action, scheduled after the end of the run); only then"},
      {"failures[].processes[]", "text", "", "Host faults only: a process that ran on the host when the fault was applied"},
      {"failures[].detected_s", "number|null", "s",
       "The target's first membership event from at_s (a rejoined for restart, resume, heal); agents' faults: the first flag; null: never"},
      {"failures[].detect_wall_ms", "number|null", "ms",
       "Wall time from the launcher applying it to the plant recording that event; null when undetected; absent for agents' faults"},
      {"failures[].recovered_s", "number|null", "s",
       "When the speed came back within 2 % of its reference for good, up to the next fault or the end (at_s: never left); null: not back, no trace"},
      {"failures[].max_speed_error_pct", "number", "%",
       "Largest |v_x - v_ref| / v_ref in trace.csv from at_s to the next fault or the end; 0 without a readable trace"},
      {"failures[].mode", "text", "",
       "Agents' faults only: open, short, torque, resistance, stuck (in the motor) or sensor, erratic, liar (in the agent)"},
      {"failures[].value", "number", "1",
       "Agents' faults only: the fault's size (torque or resistance factor, stuck V, sensor rad/s, erratic V; 0 for open, short, liar)"},
      {"failures[].injected_s", "number", "s", "Agents' faults only: when the plant applied it (the first tick at or after its scheduled time)"},
      {"failures[].isolated_s", "number|null", "s",
       "Agents' faults only: from when the agent was no longer assigned nor counted (a tick after detection); null: never"},
      {"failures[].diagnosed_mode", "text|null", "", "Agents' faults only: what the agent's group took the fault for; null when never detected"},
      {"failures[].relapses", "integer", "1", "Agents' faults only: times the agent was flagged again after a probation"},
      {"failures[].exposed_ticks", "integer", "1",
       "Agents' faults only: ticks in which the fault acted on the drive (the agent drove, or its motor carried current, while connected)"},
      {"failures[].cleared_s", "number|null", "s", "Agents' faults only: when a clear or the agent's next fault ended it; null: in force to the end"},
      {"failures[].readmitted_s", "number|null", "s",
       "Agents' faults only: when its group let the agent back after its last probation; null: never"},
      {"failures[].energy_penalty_J", "null", "J",
       "Agents' faults only: always null in a run; `maptr experiment faults` measures it against a fault-free twin"}
  };
}

/// Every membership change the plant applied (plant.membership_events, with causes).
std::vector<SummaryField> membership_keys() {
  return {
      {"membership_events[].kind", "text", "", "died, lease_lost, deadline_missed, paused, resumed, started or rejoined"},
      {"membership_events[].process", "text", "", "The process it concerns: an agent, group-L, group-R or central"},
      {"membership_events[].t_s", "number", "s", "Simulated time at which the plant applied the change"},
      {"membership_events[].wall_ms", "number", "ms", "The plant's wall clock when it applied the change, ms since the epoch"},
      {"membership_events[].cause", "text", "",
       "scheduled, chaos, command, external signal, launcher, lease, deadline or unknown; a rejoined has the cause of the change it ends"},
      {"membership_events[].after", "text", "", "Rejoined only: the kind of the process's change that it ends"}
  };
}

/// What each process dropped.
std::vector<SummaryField> rejection_keys() {
  return {
      {"rejected_samples.<process>", "integer", "1",
       "Samples this process dropped (malformed, forged, undecodable, wrong sender): plant, launcher, each follower's last report"},
      {"rejected_ready.forged", "integer", "1",
       "NodeReady samples the launcher refused: not from the participant it expects for that process, or with a wrong pid"},
      {"rejected_ready.stale", "integer", "1", "NodeReady samples from a process's participant of an earlier start (it was started again since)"},
      {"rejected_ready.malformed", "integer", "1", "NodeReady samples that break the type's rule (idl/rules.hpp)"},
      {"rejected_by_kind.plant.<kind>", "integer", "1",
       "The plant's drops by kind (forged, malformed, other_tick, conflicting, stale, undecodable) and its late answers (late)"},
      {"rejected_by_kind.launcher.<kind>", "integer", "1",
       "The launcher's drops by kind (forged, stale, malformed, undecodable); they add up to rejected_samples.launcher"}
  };
}

/// Level 2 per side, from level2-L.csv and level2-R.csv (a side without a log is absent).
std::vector<SummaryField> level2_keys() {
  return {
      {"level2.<side>.decisions", "integer", "1", "Level-2 decisions of the side's group (rows of its level2-<side>.csv; 0 in mode all)"},
      {"level2.<side>.infeasible", "integer", "1", "Decisions where no count of agents could hold the reference: every live agent ran"},
      {"level2.<side>.oracle_checked", "integer", "1", "Solved decisions that the exhaustive-search oracle also checked"},
      {"level2.<side>.oracle_differs", "integer", "1", "Checked decisions where Ipopt's integer count of active agents differed from the oracle's"},
      {"level2.<side>.solve_ms_median", "number", "ms", "Median Ipopt solve time over the side's decisions; absent with no decision"},
      {"level2.<side>.solve_ms_p95", "number", "ms", "95th percentile of the Ipopt solve time (nearest rank); absent with no decision"},
      {"level2.<side>.solve_ms_max", "number", "ms", "Longest Ipopt solve time; absent with no decision"},
      {"level2.<side>.error", "text", "", "Why the side's log could not be read (its figures are then zero); present only then"}
  };
}

/// Every process of the fleet, the plant first.
std::vector<SummaryField> process_keys() {
  return {
      {"processes[].name", "text", "",
       "The process: plant, central, group-L, group-R or an agent (L0, R3, ...)"},
      {"processes[].pid", "integer", "1",
       "Process id of its last start; an external process: the pid it reported, once checked (else -1)"},
      {"processes[].exit_code", "integer", "1",
       "Exit status of its last end; -1 when it did not exit (a signal ended it, or it was not reaped)"},
      {"processes[].signal", "integer", "1",
       "The signal that ended its last start (9: SIGKILL); 0 when none did"},
      {"processes[].max_rss_kB", "integer", "kB",
       "Peak resident memory over its starts, as wait4 reports it; 0 for an external process"},
      {"processes[].starts", "integer", "1",
       "Times the launcher started it (1 + restarts); 0 for an external process"},
      {"processes[].external", "bool", "", "True when the user started it (--external), not the launcher"},
      {"processes[].host", "text", "", "On several hosts only: the host it ran on last (h0, h1, ...)"},
      {"processes[].host_pid", "integer", "",
       "Started over ssh: its pid on its host, from its readiness (pid, exit_code, signal and max_rss_kB are "
       "its ssh client's)"},
      {"processes[].started_by", "text", "",
       "On several hosts only: the command that started it there (ssh, ip for a namespace, or the "
       "machine's own; \"\" for this machine)"}};
}

/// On several hosts only.
std::vector<SummaryField> host_keys() {
  return {{"hosts[].name", "text", "", "On several hosts only: the host's name (h0, h1, ...)"},
          {"hosts[].address", "text", "", "The host's IPv4 address"},
          {"hosts[].kind", "text", "",
           "namespace (a Linux network namespace the launcher made) or machine (a real one)"},
          {"hosts[].processes[]", "text", "", "A process placed on the host at the end of the run"},
          {"hosts[].started_by", "text", "",
           "The command that starts a process there: ssh (hosts.ssh, or a machine's ssh command), ip "
           "(ip netns exec) or \"\" (this machine)"},
          {"hosts[].discovery_server", "text", "", "The host's discovery server, address:port"},
          {"hosts[].run_folder", "text", "",
           "Where the host's processes wrote: the launcher's (this machine, or a shared disk), or its own, "
           "shipped the scenario and collected at the end into hosts/<name>/ and the run folder (\"its own: "
           "collected N files\", or \"not collected\" and why, e.g. a lost host)"},
          {"hosts[].bytes_sent", "integer|null", "B",
           "Bytes the host sent on its link during the run; null for a real machine"},
          {"hosts[].bytes_received", "integer|null", "B",
           "Bytes the host received on its link during the run; null for a real machine"},
          {"failovers[].name", "text", "",
           "On several hosts only: a controller (central, group-L, group-R) of a lost host that the launcher "
           "started again elsewhere (hosts.failover)"},
          {"failovers[].from", "text", "", "The host it was lost with"},
          {"failovers[].to", "text|null", "", "The host it runs on since; null when no host was left"},
          {"failovers[].detected_at_s", "number", "s",
           "Simulated time the host was lost (the controller died with it)"},
          {"failovers[].running_at_s", "number|null", "s",
           "Simulated time it was ready again and the plant waited for it; null if not by the end"},
          {"failovers[].ready_wall_s", "number|null", "s",
           "Wall time from its start on the new host until it was ready"},
          {"failovers[].problem", "text", "", "Why it was not started again (present only then)"}};
}

/// run.mcap against what the plant used.
std::vector<SummaryField> recording_keys() {
  return {
      {"recording", "object|null", "", "run.mcap against the answers the plant used (the keys below); null when the run recorded nothing"},
      {"recording.recorded.<topic>", "integer", "1", "Messages run.mcap holds of this topic (maptr/tick, maptr/agent_reply, ...: those of its record scope)"},
      {"recording.incomplete.<topic>.recorded", "integer", "1",
       "An answer topic of which run.mcap holds fewer messages than the plant used: the messages it holds"},
      {"recording.incomplete.<topic>.taken_by_plant", "integer", "1", "The same topic: the answers the plant used (plant.answers_taken)"},
      {"recording.rejected.<kind>", "integer", "1",
       "Messages run.mcap holds that the fleet drops (forged, undecodable, malformed), in channels whose verdict says so; maptr replay leaves them out"}
  };
}

/// A second attempt after a discovery timeout.
std::vector<SummaryField> retry_keys() {
  return {
      {"discovery_retry.first_status", "text", "",
       "Only when the first attempt timed out in discovery and the fleet ran once more: the first attempt's status"},
      {"discovery_retry.first_domain", "integer", "1", "DDS domain of the first attempt"},
      {"discovery_retry.domain", "integer", "1", "DDS domain of the second attempt, whose results these are"},
      {"discovery_retry.first_attempt", "text", "", "Folder of the run holding the first attempt's logs, summary.json and fleet.json: first-attempt/"}
  };
}

}  // namespace

const std::vector<SummaryField>& summary_fields() {
  static const std::vector<SummaryField> table = [] {
    std::vector<SummaryField> all;
    for (auto part :
         {run_keys, path_keys, failure_keys, membership_keys, rejection_keys, level2_keys, process_keys,
          host_keys, recording_keys, retry_keys, detail::plant_keys_run, detail::plant_keys_faults})
      for (auto& f : part()) all.push_back(std::move(f));
    return all;
  }();
  return table;
}

namespace {
bool documented(const std::string& path) {
  for (const auto& f : summary_fields())
    if (summary_path_matches(f.path, path)) return true;
  return false;
}

/// An empty object or list is documented when it is an entry itself or holds documented keys:
/// some entry's path begins with it ("recording.incomplete" for "recording.incomplete.<topic>.recorded").
bool documented_container(const std::string& path) {
  if (documented(path) || documented(path + "[]")) return true;
  for (const auto& f : summary_fields())
    for (std::size_t cut = f.path.find_first_of(".["); cut != std::string::npos;
         cut = f.path.find_first_of(".[", cut + 1)) {
      const std::string head = f.path.substr(0, cut);
      if (summary_path_matches(head, path)) return true;
    }
  return false;
}

/// A scalar or null must be documented under its path, an empty object or list as a container;
/// a list's entries are looked into as "a[]".
void collect_undocumented(const nlohmann::json& j, const std::string& path, std::vector<std::string>& out) {
  if (j.is_object() && !j.empty()) {
    for (const auto& [k, v] : j.items()) collect_undocumented(v, path.empty() ? k : path + "." + k, out);
  } else if (j.is_array() && !j.empty()) {
    for (const auto& e : j) collect_undocumented(e, path + "[]", out);
  } else if ((j.is_object() || j.is_array()) ? !documented_container(path) : !documented(path)) {
    out.push_back(path);
  }
}
}  // namespace

std::vector<std::string> undocumented_summary_keys(const nlohmann::json& summary) {
  std::vector<std::string> out;
  collect_undocumented(summary, "", out);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace maptr::records
