#pragma once
// The analysis of a finished run with faults: for every injected fault, when the fleet detected
// it, how long that took on the wall clock, when the body speed was back within a band around
// the reference speed, and the largest speed error in between. Free of DDS and processes.
#include <nlohmann/json.hpp>
#include <string>

namespace maptr::deploy {

/// A fault is recovered once |v_x - v_ref| / v_ref stays within this band, % (v_ref the mean
/// of the two wheel-speed references times the wheel radius).
inline constexpr double kRecoveryBandPct = 2.0;

/// Fills in detected_s, detect_wall_ms, recovered_s and max_speed_error_pct of every entry of
/// `failures` ({target, action, at_s, wall_ms}) from the plant's membership events
/// ({name, event, t_s, wall_ms}) and the trace (speed and references per tick, columns found
/// by their names in the header).
void analyse_faults(nlohmann::json& failures, const nlohmann::json& events, const std::string& trace_csv,
                    double wheel_radius_m, double recovery_band_pct = kRecoveryBandPct);

}  // namespace maptr::deploy
