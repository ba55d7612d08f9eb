#pragma once
// What a fleet's processes cost per tick, by kind: CPU µs and context switches per lock-step
// tick, from their /proc counters (deploy/studies/bench/proc_stats.hpp) read at the start and at the
// end of a measured window of ticks. Agents are given as the mean per agent and as the total;
// groups as the mean per group.
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "deploy/studies/bench/proc_stats.hpp"
#include "records/fleet_file.hpp"

namespace maptr::deploy {

enum class ProcKind { kPlant, kAgent, kGroup, kCentral, kDiscovery };

struct FleetProc {
  std::string name;
  long pid = 0;
  ProcKind kind = ProcKind::kAgent;
};

/// The fleet's processes as fleet.json names them (processes[], discovery_server_pid); the
/// launcher itself is left out.
std::vector<FleetProc> fleet_processes(const records::FleetFile& fleet);

/// Every process's counters at one moment, in fleet_processes order, and the tick then.
struct FleetSample {
  long long tick = -1;
  std::vector<std::optional<ProcCounters>> procs;
};

/// Per tick, over one kind of process.
struct KindCost {
  int processes = 0;             ///< of this kind, measured at both ends
  double cpu_us_per_tick = 0.0;  ///< summed over them
  double ctx_switches_per_tick = 0.0;
};

struct FleetCost {
  bool measured = false;  ///< a window of at least one tick with every process read at both ends
  long long ticks = 0;    ///< ticks in the window
  std::map<ProcKind, KindCost> by_kind;
};

/// The cost from `start` to `end` (same processes); not measured when the window holds no tick
/// or a process could not be read at either end.
FleetCost fleet_cost(const std::vector<FleetProc>& procs, const FleetSample& start, const FleetSample& end);

/// The bench's columns of a cost (cs_tick_* and cpu_us_tick_*: plant, agent (mean), agents
/// (total), group (mean), central, ds), zeros when not measured.
nlohmann::json fleet_cost_json(const FleetCost& c);

}  // namespace maptr::deploy
