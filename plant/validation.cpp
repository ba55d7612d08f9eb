#include "plant/validation.hpp"

#include <cmath>

namespace maptr::plant {

bool valid(const msg::AgentReply& r, const SampleLimits& l) {
  return r.side() <= 1 && r.index() < l.per_side && std::isfinite(r.voltage_V()) &&
         std::isfinite(r.current_A()) && std::isfinite(r.efficiency()) && r.voltage_V() >= 0.0 &&
         r.voltage_V() <= l.battery_V[r.side()] + l.voltage_tolerance_V && r.state() <= msg::AGENT_STOPPING;
}

bool valid(const msg::GroupStatus& g, const SampleLimits& l) {
  return g.side() <= 1 && g.active().size() == static_cast<std::size_t>(l.per_side);
}

bool valid(const msg::CentralCommand& c, const SampleLimits& l) {
  return std::isfinite(c.phidot_ref_L()) && std::isfinite(c.phidot_ref_R()) &&
         std::fabs(c.phidot_ref_L()) < l.ref_bound_radps && std::fabs(c.phidot_ref_R()) < l.ref_bound_radps;
}

bool drives(const msg::AgentReply& r) {
  return r.state() == msg::AGENT_ACTIVE || r.state() == msg::AGENT_HOLDING ||
         r.state() == msg::AGENT_STOPPING;
}

}  // namespace maptr::plant
