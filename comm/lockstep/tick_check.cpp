#include "comm/lockstep/tick_check.hpp"

#include <cmath>
#include <limits>

#include "idl/rules.hpp"

namespace maptr::comm {

bool tick_valid(const msg::PlantTick& t, std::size_t per_side) {
  msg::FleetBounds b;
  b.per_side = per_side;
  return msg::well_formed(t, b);  // the rule beside the IDL type (idl/rules.hpp)
}

TickVerdict classify_tick(const msg::PlantTick& t, std::size_t per_side, long long last_tick) {
  if (!tick_valid(t, per_side)) return TickVerdict::kRejected;
  // Ticks count from 0: one beyond the range of long long is as malformed as a NaN.
  const unsigned long long k = t.tick();
  if (k > static_cast<unsigned long long>(std::numeric_limits<long long>::max()))
    return TickVerdict::kRejected;
  const long long tick = static_cast<long long>(k);
  if (tick == last_tick) return TickVerdict::kRepeat;
  return tick > last_tick ? TickVerdict::kNew : TickVerdict::kRejected;
}

bool tick_wakes_agent(const msg::PlantTick& t, int side, int index) {
  if (t.run_state() != msg::RUN_RUNNING) return true;
  const long long k = static_cast<long long>(t.tick());
  // Fresh as the agent's core counts it (control/level1/agent_core.cpp): the command of tick k-1.
  const auto fresh = [k](long long stamp) { return stamp >= 0 && k - stamp <= 1; };
  if (!fresh(t.central_stamp())) return true;
  if (side < 0 || side > 1) return true;
  const msg::SideTick& own = t.sides()[static_cast<std::size_t>(side)];
  if (!fresh(own.group_stamp())) return true;
  const auto i = static_cast<std::size_t>(index);
  if (index < 0 || i >= own.wake().size() || i >= own.active().size()) return true;
  return own.wake()[i] != 0 || own.active()[i] != 0;
}

}  // namespace maptr::comm
