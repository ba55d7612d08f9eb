#pragma once
// Fault injection support for the launcher, free of DDS and processes:
//   - a random fault schedule reproducible from a seed (--chaos SEED);
//   - the analysis of a finished run: for every injected fault, when the fleet detected it,
//     how long that took on the wall clock, when the speed was back within 2% of the
//     reference, and the largest speed error in between.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/scenario.hpp"

namespace maptr::deploy {

/// Kills and restarts of agents and controllers (never the plant) at random simulated times,
/// the same for the same seed and scenario. Every killed process is restarted 2-8 s later.
std::vector<config::FaultSpec> chaos_schedule(unsigned seed, const config::Scenario& s, int faults = 4);

/// Fills in detected_s, detect_wall_ms, recovered_s and max_speed_error_pct of every entry of
/// `failures` ({target, action, at_s, wall_ms}) from the plant's membership events
/// ({name, event, t_s, wall_ms}) and the trace (speed and references per tick).
void analyse_faults(nlohmann::json& failures, const nlohmann::json& events, const std::string& trace_csv,
                    double wheel_radius_m, double recovery_band_pct = 2.0);

}  // namespace maptr::deploy
