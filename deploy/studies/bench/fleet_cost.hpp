#pragma once
// What a fleet's processes cost per tick, by kind: CPU µs and context switches per lock-step
// tick, from their /proc counters (deploy/studies/bench/proc_stats.hpp) read at the start and at the
// end of a measured window of ticks. Agents are given as the mean per agent and as the total;
// groups as the mean per group. The launcher (with run.mcap's recorder) and the discovery server
// count too, and the same CPU is split by thread: the lock-step processes' main threads (the
// tick path), the Level-2 solvers, the recorder, and every other thread (Fast DDS's, logging, the
// launcher's loop). Beside them, what the machine's CPUs ran over the window (/proc/stat) and the
// bench's own watch: the columns add up to the machine's figure, less what nothing here ran.
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "deploy/studies/bench/proc_stats.hpp"
#include "records/fleet_file.hpp"

namespace maptr::deploy {

enum class ProcKind { kPlant, kAgent, kGroup, kCentral, kDiscovery, kLauncher };

struct FleetProc {
  std::string name;
  long pid = 0;
  ProcKind kind = ProcKind::kAgent;
};

/// The fleet's processes as fleet.json names them (processes[], discovery_server_pid), and the
/// launcher (launcher_pid) when the file names it.
std::vector<FleetProc> fleet_processes(const records::FleetFile& fleet);

/// Every process's counters at one moment, in fleet_processes order, and the tick then.
struct FleetSample {
  long long tick = -1;
  std::vector<std::optional<ProcCounters>> procs;
  std::optional<MachineCpu> machine;  ///< the machine's CPU counters then
  double watcher_cpu_s = 0.0;         ///< the bench's own process so far (its watch), s
};

/// Per tick, over one kind of process.
struct KindCost {
  int processes = 0;             ///< of this kind, measured at both ends
  double cpu_us_per_tick = 0.0;  ///< summed over them
  double ctx_switches_per_tick = 0.0;
};

/// Per tick, over every process, by thread.
struct ThreadCost {
  double tick_path_us = 0.0;  ///< main threads of plant, agents, groups and central
  double level2_us = 0.0;     ///< the groups' "level2" threads
  double recorder_us = 0.0;   ///< the launcher's "recorder" thread
  double other_us = 0.0;      ///< every other thread: Fast DDS's, logging, the launcher's and the server's
};

struct FleetCost {
  bool measured = false;  ///< a window of at least one tick with every process read at both ends
  long long ticks = 0;    ///< ticks in the window
  std::map<ProcKind, KindCost> by_kind;
  ThreadCost threads;
  double machine_us_per_tick = 0.0;  ///< busy CPU of the whole machine (0: /proc/stat not read)
  double watcher_us_per_tick = 0.0;  ///< the bench's own process
};

/// The cost from `start` to `end` (same processes); not measured when the window holds no tick
/// or a process could not be read at either end.
FleetCost fleet_cost(const std::vector<FleetProc>& procs, const FleetSample& start, const FleetSample& end);

/// The bench's columns of a cost (cs_tick_* and cpu_us_tick_*: plant, agent (mean), agents
/// (total), group (mean), groups, central, ds, launcher; by thread: tick path, level2, recorder,
/// other; the sum of the processes, the watch, the machine and how much of it is accounted for),
/// zeros when not measured.
nlohmann::json fleet_cost_json(const FleetCost& c);

}  // namespace maptr::deploy
