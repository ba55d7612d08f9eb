#pragma once
// Two-term exponential battery (paper Sec. "Battery Model"): V_B = h e^{w d} + y e^{z d},
// d = discharge in mAh. One battery per group.
#include "model/params.hpp"

namespace maptr::model {

/// Battery terminal voltage after d_mAh of discharge, V (never below 0).
double battery_voltage(const BatteryParams& b, double discharge_mAh);

}  // namespace maptr::model
