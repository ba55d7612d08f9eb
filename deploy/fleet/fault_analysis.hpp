#pragma once
// The analysis of a finished run with faults: for every injected fault, when the fleet detected
// it, how long that took on the wall clock, when the body speed was back within a band around
// the reference speed, and the largest speed error in between. Free of DDS and processes.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "plant_core/speed_band.hpp"
#include "records/plant_results.hpp"

namespace maptr::deploy {

/// Fills in detected_s, detect_wall_ms, recovered_s and max_speed_error_pct of every entry of
/// `failures` ({target, action, at_s, wall_ms}) from the plant's membership events and the trace
/// (records::read_trace). A fault is recovered once |v_x - v_ref| / v_ref stays within recovery_band_pct
/// (v_ref the trace row's reference speed). Without a readable trace, recovered_s is null and
/// max_speed_error_pct 0.
void analyse_faults(nlohmann::json& failures, const std::vector<records::MembershipEvent>& events,
                    const std::string& trace_csv, double wheel_radius_m,
                    double recovery_band_pct = plant_core::kSpeedBandPct);

}  // namespace maptr::deploy
