#pragma once
// The events `maptr top` shows, from what a run wrote: the scheduled faults of its scenario by
// gate tick (a live run's gates name their faults), and a finished run's whole event record
// (summary.json: the faults, the membership events and its groups' isolations) for a replay,
// which then shows exactly the live run's events in simulated-time order. Pure.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "deploy/top/fleet_view.hpp"

namespace maptr::top {

/// Per fault-gate tick, what the scenario schedules there ("kill of L3, restart of L1"); the
/// agents' own faults (fault, clear) have no gate and are left out.
std::map<long long, std::string> gate_faults(const config::Scenario& s);

/// A finished run's events in simulated-time order (ties in the order written): every fault
/// applied ("scheduled kill of L3 (tick 1500)", "chaos pause of central (tick 800)"), every
/// membership event ("L3 died (scheduled)"), every isolation and re-admission by a group ("L3
/// isolated by its group (open)"). `tick_hz` turns a fault's time into its tick.
std::vector<ViewEvent> recorded_events(const nlohmann::json& summary, double tick_hz);

}  // namespace maptr::top
