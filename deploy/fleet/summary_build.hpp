#pragma once
// summary.json of a run: the scenario, the plant's results (RUN_DIR/plant.json), the launch
// (discovery time, restarts of the discovery server, transport), every fault with its
// analysis, the Level-2 figures of the groups, every process's end and the trace's hash.
// Experiments and tests read its keys. Free of DDS.
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "deploy/fleet/children.hpp"
#include "deploy/fleet/plant_clock.hpp"
#include "records/plant_results.hpp"

namespace maptr::deploy::fleet {

/// What the launcher saw of a run.
struct RunRecord {
  std::string status = "ok";  ///< "ok" or "aborted: ..." as the launcher ended the run
  double discovery_s = 0.0;   ///< wall time until every process was ready, s
  double run_wall_s = 0.0;    ///< wall time from the start to the plant's end, s
  int discovery_restarts = 0;
  std::vector<std::string> rematched;  ///< processes started again during discovery (not ready in time)
  std::string transport;                              ///< "shm" or "udp"
  std::string agent_start;                            ///< "zygote" (forked) or "exec"
  long long chaos_seed = -1;                          ///< recorded when >= 0
  PlantState last_tick;                               ///< the plant's last tick the launcher saw
  nlohmann::json failures = nlohmann::json::array();  ///< the fault records
  long launcher_rejected = 0;  ///< ticks and fault gates the launcher dropped (not from the plant)
  /// NodeReady samples the launcher did not believe, by kind ("forged", "stale"); counted in
  /// launcher_rejected too.
  std::map<std::string, long> ready_rejected;
  /// Every sample the launcher dropped, by kind (forged, stale, malformed, undecodable).
  std::map<std::string, long> launcher_by_kind;
  nlohmann::json hosts;  ///< a fleet on several hosts: its hosts (else null)
  nlohmann::json
      failovers;  ///< a fleet on several hosts: the controllers started again elsewhere (else null)
  /// Messages run.mcap recorded per topic (empty without a recording).
  std::map<std::string, uint64_t> recorded;
  /// Messages run.mcap marks as dropped by the fleet, by verdict (recorder/sample_verdict.hpp).
  std::map<std::string, uint64_t> recorded_rejected;
};

/// The run's status with its recording: an `ok` run whose run.mcap holds fewer messages on a
/// topic than the plant used (recording_check's "incomplete") is "degraded: run.mcap incomplete:
/// <topic> holds N of the M samples the plant used, ..."; any other status as it is.
std::string recording_status(const std::string& status, const nlohmann::json& recording);

/// run.mcap against what the plant used: {"recorded": {topic: n}, "incomplete": {topic:
/// {"recorded": n, "taken_by_plant": m}}} for each topic of which run.mcap holds fewer messages
/// than the plant used answers (every answer it used was sent to the recorder too); null without
/// a recording.
nlohmann::json recording_check(const std::map<std::string, uint64_t>& recorded,
                               const std::optional<records::PlantResults>& plant);

/// The run's status: the launcher's if it aborted, else the plant's ("unknown" without one),
/// or an abort naming the plant's exit when the plant left no results.
std::string final_status(const std::string& launch_status, const std::optional<records::PlantResults>& plant,
                         const Child& plant_child);

/// Level-2 figures from the groups' level2-<side>.csv (records::read_level2_log): decisions,
/// infeasible decisions, Ipopt solve time (median, p95, max) and, where the oracle ran on a
/// solved problem, how often Ipopt's integer differed. A side without a log is absent; a side
/// whose log cannot be read has no decisions and an "error".
nlohmann::json level2_stats(const std::string& run_dir);

/// A scenario file of the project by its path in the project (results are committed and must
/// not carry the paths of the machine that made them); others as given.
std::string scenario_file(const std::string& source, const std::string& project_root);

/// Every process's end: name, pid, exit_code, signal, max_rss_kB, starts, external.
nlohmann::json processes_json(const std::vector<Child>& kids);

/// The summary of a run (kids.front() is the plant); the fault records are analysed against
/// the plant's membership events and RUN_DIR/trace.csv.
nlohmann::json build_summary(const config::Scenario& sc, const std::string& project_root, const RunRecord& r,
                             const std::string& run_dir, const std::vector<Child>& kids);

}  // namespace maptr::deploy::fleet

namespace maptr::deploy {
/// Short human summary of a summary.json.
std::string human_summary(const nlohmann::json& s);
}  // namespace maptr::deploy
