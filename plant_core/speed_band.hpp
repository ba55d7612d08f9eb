#pragma once
// The band around the reference speed within which the robot holds it:
//   |v_x - v_ref| / v_ref < kSpeedBandPct / 100,   v_ref = (phidot_ref_L + phidot_ref_R) r / 2.
// The plant counts the reference as reached the first time the speed enters it, a fault as
// recovered once the speed is back in it, and the experiments take their reach time from it.
namespace maptr::plant_core {

/// Relative speed band around the reference, %.
inline constexpr double kSpeedBandPct = 2.0;

}  // namespace maptr::plant_core
