#include "comm/tick_check.hpp"

#include <cmath>
#include <limits>

namespace maptr::comm {

namespace {
/// V_active is the mean of tick k-1's voltages, clamped to that tick's battery voltage; the
/// battery's voltage at t_k may be a little lower.
constexpr double kVoltageMargin = 1.01;

bool side_valid(const msg::SideTick& s, std::size_t per_side) {
  for (double v : {s.phidot(), s.battery_V(), s.discharge_mAh(), s.phidot_ref(), s.V_active(), s.phidot_prev(),
                   s.phidot_ref_prev()})
    if (!std::isfinite(v)) return false;
  return s.active().size() == per_side && s.live().size() == per_side && s.wake().size() == per_side &&
         s.battery_V() >= 0 &&
         s.V_active() >= -kVoltageMargin * s.battery_V() && s.n_active() <= per_side && s.relay_count() <= per_side;
}
}  // namespace

bool tick_valid(const msg::PlantTick& t, std::size_t per_side) {
  for (double v : {t.t(), t.dt(), t.x(), t.y(), t.theta(), t.v_x(), t.w(), t.energy_J(), t.distance_m()})
    if (!std::isfinite(v)) return false;
  if (t.run_state() > msg::RUN_ABORTED) return false;
  for (const msg::SideTick& s : t.sides())
    if (!side_valid(s, per_side)) return false;
  // The paused mask: empty, or one entry per member (agents, groups, central).
  return t.paused().empty() || t.paused().size() == 2 * per_side + 3;
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
