#include "control/level3/ledger.hpp"

namespace maptr::control {

void Ledger::accrue(const std::vector<uint8_t>& active, double distance_m, double dt_s) {
  for (std::size_t j = 0; j < wear_m.size(); ++j) {
    if (j < active.size() && active[j]) {
      wear_m[j] += distance_m;
      active_time_s[j] += dt_s;
    } else {
      active_time_s[j] = 0.0;
    }
  }
}

}  // namespace maptr::control
