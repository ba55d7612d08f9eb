#pragma once
// The checks of `maptr soak` on one finished fleet, free of DDS and processes: its status (ok,
// or degraded with its reason), the groups' wear ledgers (never going backwards while the run
// went on, never lost at its end) and its distance and energy within a band of the fault-free
// run of the same scenario. Also the fault schedule of each fleet of a soak and the count of
// its faults by kind.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/scenario.hpp"

namespace maptr::deploy::soak {

/// How far a fleet with faults may end from the fault-free run of its scenario, % of the
/// fault-free figure: the distance may fall short by up to distance_below_pct (an outage of
/// central stops the robot for its length) and exceed it by up to distance_above_pct; the
/// energy may differ by up to energy_pct either way.
struct Band {
  double distance_below_pct = 35.0;
  double distance_above_pct = 2.0;
  double energy_pct = 35.0;
};

/// Wear [m] a final ledger file may have below the last ledger the plant saw (rounding).
inline constexpr double kLedgerToleranceM = 1e-6;

/// The seed of fleet `index` of a soak of seed `seed` (distinct fleets, distinct schedules).
unsigned fleet_seed(unsigned seed, int index);

/// The faults of fleet `index`: `outages` random outages (kills, pauses; agents, groups,
/// central and the discovery server), reproducible from the soak's seed.
std::vector<config::FaultSpec> fleet_faults(unsigned seed, int index, const config::Scenario& s, int outages);

/// Faults applied by kind ("kill", "restart", "pause", "resume") and "skipped", from the
/// summary's failures.
std::map<std::string, int> faults_by_kind(const nlohmann::json& summary);

/// What the soak does to a fleet's launcher still running elapsed_s after its start: nothing,
/// SIGTERM once past timeout_s (the launcher ends its fleet), SIGKILL once past timeout_s +
/// grace_s (a launcher that does not end; the soak then kills the fleet's processes itself).
enum class Deadline { kNone, kTerm, kKill };
Deadline fleet_deadline(double elapsed_s, double timeout_s, double grace_s);

/// "" when the status is ok or "degraded: <reason>", else why it fails.
std::string check_status(const nlohmann::json& summary);

/// Failures of the wear ledgers: a regression the plant saw (summary.plant.group_wear), a
/// ledger file RUN_DIR/ledger-{L,R}.json missing or unreadable, of the wrong size, or below
/// the last ledger the plant saw (lost wear).
std::vector<std::string> check_wear(const nlohmann::json& summary, const std::string& run_dir, int per_side);

/// Signed deviation of `value` from `reference`, % of the reference (0 when it is 0).
double deviation_pct(double value, double reference);

/// Failures of distance and energy against the fault-free summary `reference`.
/// The groups' detection: every healthy agent they isolated (a false detection), by name and
/// time; empty when none.
std::vector<std::string> check_detection(const nlohmann::json& summary);

std::vector<std::string> check_band(const nlohmann::json& summary, const nlohmann::json& reference,
                                    const Band& b);

}  // namespace maptr::deploy::soak
