#include "deploy/studies/bench/fleet_cost.hpp"

#include <algorithm>

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
  if (fleet.launcher_pid > 0) out.push_back({"launcher", fleet.launcher_pid, ProcKind::kLauncher});
  return out;
}

namespace {

/// A process's CPU split by thread into `t`, µs per tick.
void add_threads(ThreadCost& t, ProcKind kind, const ProcCounters& a, const ProcCounters& b, double ticks) {
  const auto us = [&](double s) { return s * 1e6 / ticks; };
  const auto named = [&](const char* name) {
    const auto at = [&](const ProcCounters& c) { return c.named_cpu_s.count(name) ? c.named_cpu_s.at(name) : 0.0; };
    return std::max(0.0, at(b) - at(a));  // a thread that ended in the window: counted with the rest
  };
  const double whole = us(b.cpu_s - a.cpu_s), level2 = us(named(comm::kLevel2Thread)),
               recorder = us(named(comm::kRecorderThread));
  const bool lock_step = kind != ProcKind::kDiscovery && kind != ProcKind::kLauncher;
  const double main = lock_step ? us(std::max(0.0, b.main_cpu_s - a.main_cpu_s)) : 0.0;
  t.tick_path_us += main;
  t.level2_us += level2;
  t.recorder_us += recorder;
  t.other_us += std::max(0.0, whole - main - level2 - recorder);
}

}  // namespace

FleetCost fleet_cost(const std::vector<FleetProc>& procs, const FleetSample& start, const FleetSample& end) {
  FleetCost c;
  c.ticks = end.tick - start.tick;
  if (c.ticks <= 0 || start.procs.size() != procs.size() || end.procs.size() != procs.size()) return c;
  const double ticks = static_cast<double>(c.ticks);
  for (std::size_t i = 0; i < procs.size(); ++i) {
    if (!start.procs[i] || !end.procs[i]) return FleetCost{false, c.ticks, {}, {}, 0.0, 0.0};
    KindCost& k = c.by_kind[procs[i].kind];
    ++k.processes;
    k.cpu_us_per_tick += (end.procs[i]->cpu_s - start.procs[i]->cpu_s) * 1e6 / ticks;
    k.ctx_switches_per_tick +=
        static_cast<double>(end.procs[i]->ctx_switches - start.procs[i]->ctx_switches) / ticks;
    add_threads(c.threads, procs[i].kind, *start.procs[i], *end.procs[i], ticks);
  }
  if (start.machine && end.machine)
    c.machine_us_per_tick = clock_ticks_s(end.machine->busy - start.machine->busy) * 1e6 / ticks;
  c.watcher_us_per_tick = (end.watcher_cpu_s - start.watcher_cpu_s) * 1e6 / ticks;
  c.measured = true;
  return c;
}

nlohmann::json fleet_cost_json(const FleetCost& c) {
  auto get = [&](ProcKind k) { return c.by_kind.count(k) ? c.by_kind.at(k) : KindCost{}; };
  const KindCost agents = get(ProcKind::kAgent), groups = get(ProcKind::kGroup);
  const std::pair<const char*, ProcKind> kinds[] = {{"plant", ProcKind::kPlant},   {"agents", ProcKind::kAgent},
                                                    {"groups", ProcKind::kGroup},  {"central", ProcKind::kCentral},
                                                    {"ds", ProcKind::kDiscovery}, {"launcher", ProcKind::kLauncher}};
  nlohmann::json j = {{"cost_ticks", c.measured ? c.ticks : 0}};
  double processes = 0.0;
  for (const auto& [name, kind] : kinds) {
    j[std::string("cs_tick_") + name] = get(kind).ctx_switches_per_tick;
    j[std::string("cpu_us_tick_") + name] = get(kind).cpu_us_per_tick;
    processes += get(kind).cpu_us_per_tick;
  }
  j["cs_tick_agent"] = per_process(agents.ctx_switches_per_tick, agents.processes);
  j["cpu_us_tick_agent"] = per_process(agents.cpu_us_per_tick, agents.processes);
  j["cs_tick_group"] = per_process(groups.ctx_switches_per_tick, groups.processes);
  j["cpu_us_tick_group"] = per_process(groups.cpu_us_per_tick, groups.processes);
  const ThreadCost& t = c.threads;
  j.update({{"cpu_us_tick_tick_path", t.tick_path_us},
            {"cpu_us_tick_level2", t.level2_us},
            {"cpu_us_tick_recorder", t.recorder_us},
            {"cpu_us_tick_other_threads", t.other_us},
            {"cpu_us_tick_processes", processes},
            {"cpu_us_tick_watch", c.watcher_us_per_tick},
            {"cpu_us_tick_machine", c.machine_us_per_tick}});
  const double accounted = processes + c.watcher_us_per_tick;
  j["cpu_accounted_pct"] = c.machine_us_per_tick > 0 ? 100.0 * accounted / c.machine_us_per_tick : 0.0;
  return j;
}

}  // namespace maptr::deploy
