#include "deploy/studies/bench/fleet_cost.hpp"

namespace maptr::deploy {

namespace {

ProcKind kind_of(const std::string& name) {
  if (name == "plant") return ProcKind::kPlant;
  if (name == "central") return ProcKind::kCentral;
  if (name.rfind("group-", 0) == 0) return ProcKind::kGroup;
  return ProcKind::kAgent;
}

/// A kind's cost per process of it (0 when there is none).
double per_process(double total, int n) { return n > 0 ? total / n : 0.0; }

}  // namespace

std::vector<FleetProc> fleet_processes(const records::FleetFile& fleet) {
  std::vector<FleetProc> out;
  // Over ssh the process itself, not its ssh client.
  for (const auto& p : fleet.processes) out.push_back({p.name, p.host_pid.value_or(p.pid), kind_of(p.name)});
  if (fleet.discovery_server_pid)
    out.push_back({"discovery-server", *fleet.discovery_server_pid, ProcKind::kDiscovery});
  return out;
}

FleetCost fleet_cost(const std::vector<FleetProc>& procs, const FleetSample& start, const FleetSample& end) {
  FleetCost c;
  c.ticks = end.tick - start.tick;
  if (c.ticks <= 0 || start.procs.size() != procs.size() || end.procs.size() != procs.size()) return c;
  const double ticks = static_cast<double>(c.ticks);
  for (std::size_t i = 0; i < procs.size(); ++i) {
    if (!start.procs[i] || !end.procs[i]) return FleetCost{false, c.ticks, {}};
    KindCost& k = c.by_kind[procs[i].kind];
    ++k.processes;
    k.cpu_us_per_tick += (end.procs[i]->cpu_s - start.procs[i]->cpu_s) * 1e6 / ticks;
    k.ctx_switches_per_tick +=
        static_cast<double>(end.procs[i]->ctx_switches - start.procs[i]->ctx_switches) / ticks;
  }
  c.measured = true;
  return c;
}

nlohmann::json fleet_cost_json(const FleetCost& c) {
  auto get = [&](ProcKind k) { return c.by_kind.count(k) ? c.by_kind.at(k) : KindCost{}; };
  const KindCost plant = get(ProcKind::kPlant), agents = get(ProcKind::kAgent),
                 groups = get(ProcKind::kGroup), central = get(ProcKind::kCentral),
                 ds = get(ProcKind::kDiscovery);
  return {{"cost_ticks", c.measured ? c.ticks : 0},
          {"cs_tick_plant", plant.ctx_switches_per_tick},
          {"cs_tick_agent", per_process(agents.ctx_switches_per_tick, agents.processes)},
          {"cs_tick_agents", agents.ctx_switches_per_tick},
          {"cs_tick_group", per_process(groups.ctx_switches_per_tick, groups.processes)},
          {"cs_tick_central", central.ctx_switches_per_tick},
          {"cs_tick_ds", ds.ctx_switches_per_tick},
          {"cpu_us_tick_plant", plant.cpu_us_per_tick},
          {"cpu_us_tick_agent", per_process(agents.cpu_us_per_tick, agents.processes)},
          {"cpu_us_tick_agents", agents.cpu_us_per_tick},
          {"cpu_us_tick_group", per_process(groups.cpu_us_per_tick, groups.processes)},
          {"cpu_us_tick_central", central.cpu_us_per_tick},
          {"cpu_us_tick_ds", ds.cpu_us_per_tick}};
}

}  // namespace maptr::deploy
