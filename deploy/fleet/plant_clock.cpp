#include "deploy/fleet/plant_clock.hpp"

#include <algorithm>

namespace maptr::deploy::fleet {

bool PlantClock::from_plant(const GuidPrefix& writer) {
  const bool ok = plant_ && *plant_ == writer;
  if (!ok) ++rejected_;
  return ok;
}

bool PlantClock::on_tick(const GuidPrefix& writer, const PlantState& s) {
  if (!from_plant(writer)) return false;
  state_ = s;
  return true;
}

}  // namespace maptr::deploy::fleet
