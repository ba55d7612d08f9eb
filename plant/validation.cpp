#include "plant/validation.hpp"

#include <cmath>

namespace maptr::plant {

bool valid(const msg::AgentReply& r, const SampleLimits& l) {
  if (r.side() > msg::SIDE_R) return false;
  const double limit = l.battery_V[r.side()] + l.voltage_tolerance_V;
  const double floor = l.bidirectional ? -limit : 0.0;
  return r.index() < l.per_side && std::isfinite(r.voltage_V()) && std::isfinite(r.current_A()) &&
         std::isfinite(r.efficiency()) && r.voltage_V() >= floor && r.voltage_V() <= limit &&
         r.state() <= msg::AGENT_STOPPING;
}

bool valid(const msg::GroupStatus& g, const SampleLimits& l) {
  return g.side() <= msg::SIDE_R && g.active().size() == static_cast<std::size_t>(l.per_side);
}

bool valid(const msg::CentralCommand& c, const SampleLimits& l) {
  for (double ref : c.phidot_ref())
    if (!std::isfinite(ref) || std::fabs(ref) >= l.ref_bound_radps) return false;
  // A relayed count is the other side's active agents: at most a side's agents.
  for (unsigned short n : c.relay_count_for())
    if (n > l.per_side) return false;
  return true;
}

LauncherEvent launcher_event(msg::MemberEvent kind) {
  switch (kind) {
    case msg::MEMBER_DIED:
      return LauncherEvent::kDied;
    case msg::MEMBER_STARTED:
      return LauncherEvent::kStarted;
    case msg::MEMBER_PAUSED:
      return LauncherEvent::kPaused;
    case msg::MEMBER_RESUMED:
      return LauncherEvent::kResumed;
  }
  return LauncherEvent::kOther;
}

bool drives(const msg::AgentReply& r) {
  return r.state() == msg::AGENT_ACTIVE || r.state() == msg::AGENT_HOLDING ||
         r.state() == msg::AGENT_STOPPING;
}

}  // namespace maptr::plant
