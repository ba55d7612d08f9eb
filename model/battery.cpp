#include "model/battery.hpp"

#include <algorithm>
#include <cmath>

namespace maptr::model {

double battery_voltage(const BatteryParams& b, double d) {
  return std::max(0.0, b.h * std::exp(b.w * d) + b.y * std::exp(b.z * d));
}

}  // namespace maptr::model
