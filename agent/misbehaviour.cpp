#include "agent/misbehaviour.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "model/motor.hpp"

namespace maptr::agent {

namespace {
/// splitmix64: a well-mixed 64-bit hash.
uint64_t mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
double unit(uint64_t h) { return (static_cast<double>(h >> 11) + 0.5) * (1.0 / 9007199254740992.0); }  // (0, 1)
}  // namespace

double seeded_noise(long long tick, int side, int index) {
  const uint64_t key = (static_cast<uint64_t>(tick) << 20) ^ (static_cast<uint64_t>(side) << 19) ^
                       static_cast<uint64_t>(index);
  const double u1 = unit(mix(key)), u2 = unit(mix(key ^ 0x5bd1e995ULL));
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);  // Box-Muller
}

FaultyAgent::FaultyAgent(const control::AgentConfig& c, std::vector<MisbehaviourEvent> events, int side, int index)
    : c_(c), core_(c), events_(std::move(events)), side_(side), index_(index) {
  std::stable_sort(events_.begin(), events_.end(), [](auto& a, auto& b) { return a.tick < b.tick; });
}

control::AgentOutput FaultyAgent::step(control::AgentInput in) {
  now_ = MisbehaviourEvent{};
  for (const auto& e : events_)
    if (e.tick <= in.tick) now_ = e;
  switch (now_.kind) {
    case Misbehaviour::kNone:
      return core_.step(in);
    case Misbehaviour::kSensor: {
      in.phidot_rad_s += now_.value;
      in.phidot_prev_rad_s += now_.value;
      return core_.step(in);
    }
    case Misbehaviour::kErratic: {
      control::AgentOutput out = core_.step(in);
      if (!out.drives()) return out;
      out.voltage_V = std::clamp(out.voltage_V + now_.value * seeded_noise(in.tick, side_, index_),
                                 c_.driver.floor_V(in.battery_V), in.battery_V);
      out.current_A = model::armature_current(c_.motor, c_.driver, out.voltage_V, in.phidot_rad_s);
      out.efficiency = model::efficiency(c_.motor, c_.driver, out.voltage_V, in.phidot_rad_s);
      return out;
    }
    case Misbehaviour::kLiar: {
      control::AgentOutput out = core_.step(in);  // the healthy agent it pretends to be
      if (out.drives()) out.voltage_V = in.battery_V;
      return out;
    }
  }
  return core_.step(in);
}

}  // namespace maptr::agent
