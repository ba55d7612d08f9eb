#pragma once
// What agent `index` of `side` reads from a PlantTick for its core (no DDS: the generated
// message type only). The agent node and the tests that step a core on ticks use this one map.
#include <cstddef>

#include "control/level1/agent_core.hpp"
#include "idl/maptr.h"

namespace maptr::agent {

inline control::AgentInput agent_input(const msg::PlantTick& t, int side, int index) {
  const msg::SideTick& own = t.sides()[static_cast<std::size_t>(side)];
  control::AgentInput in;
  in.tick = static_cast<long long>(t.tick());
  in.phidot_rad_s = own.phidot();
  in.battery_V = own.battery_V();
  in.side_active_V = own.V_active();
  in.phidot_ref_rad_s = own.phidot_ref();
  in.central_stamp = t.central_stamp();
  in.group_stamp = own.group_stamp();
  in.assigned = own.active()[static_cast<std::size_t>(index)] != 0;
  in.phidot_prev_rad_s = own.phidot_prev();
  in.phidot_ref_prev_rad_s = own.phidot_ref_prev();
  return in;
}

}  // namespace maptr::agent
