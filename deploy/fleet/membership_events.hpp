#pragma once
// The membership changes of a run, for summary.json: every change the plant recorded (died,
// lease lost, deadline missed, paused, resumed, started, rejoined) with the process, the
// simulated time (s) and the wall clock (ms since the epoch) at which the plant applied it, and
// its cause, found in the launcher's fault records: a fault from the scenario ("scheduled"),
// from --chaos ("chaos") or from `maptr kill|restart|pause|resume` ("command"); a death no
// fault explains is an "external signal"; a lost lease is the "lease"; a missed deadline the
// "deadline"; a rejoin has the cause of the process's previous change. Free of DDS.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "records/plant_results.hpp"

namespace maptr::deploy {

/// The kind of a plant membership record ("died (launcher)" -> "died", "lost (DDS liveliness)"
/// -> "lease_lost", ...); an unknown record is its own kind.
std::string membership_kind(const std::string& plant_event);

/// plant_events: the plant's records (plant.json membership_events); failures: the launcher's
/// fault records ({target, action, at_s, wall_ms, origin[, skipped]}). Returns
/// [{kind, process, t_s, wall_ms, cause[, after]}] in the plant's order; `after` (rejoined
/// only) is the kind of the change it ends.
nlohmann::json membership_events(const std::vector<records::MembershipEvent>& plant_events,
                                 const nlohmann::json& failures);

}  // namespace maptr::deploy
