#include "plant/validation.hpp"

#include <cmath>

#include "config/scenario.hpp"
#include "idl/rules.hpp"

namespace maptr::plant {

namespace {
msg::FleetBounds bounds(const SampleLimits& l) {
  msg::FleetBounds b;
  b.per_side = static_cast<std::size_t>(l.per_side > 0 ? l.per_side : 0);
  b.ref_bound_radps = l.ref_bound_radps;
  b.v_bound_mps = l.v_bound_mps;
  b.w_bound_radps = l.w_bound_radps;
  return b;
}
}  // namespace

bool well_formed(const msg::AgentReply& r, const SampleLimits& l) { return msg::well_formed(r, bounds(l)); }

bool valid(const msg::AgentReply& r, const SampleLimits& l) {
  // The rule beside the IDL type, and a voltage the side's driver can apply with the side's
  // battery now: [0, V_B], or [-V_B, V_B] with an H-bridge.
  if (!well_formed(r, l)) return false;
  const double limit = l.battery_V[r.side()] + l.voltage_tolerance_V;
  return r.voltage_V() <= limit && r.voltage_V() >= (l.bidirectional ? -limit : 0.0);
}

bool valid(const msg::GroupStatus& g, const SampleLimits& l) { return msg::well_formed(g, bounds(l)); }

bool valid(const msg::CentralCommand& c, const SampleLimits& l) { return msg::well_formed(c, bounds(l)); }

bool valid(const msg::MembershipEvent& e, const SampleLimits& l) {
  if (!msg::well_formed(e, bounds(l))) return false;
  const std::string& n = e.name();
  int side = 0, index = 0;
  if (config::parse_agent_name(n, side, index))
    return e.node_kind() == msg::NODE_AGENT && index < l.per_side && e.side() == side && e.index() == index;
  if (n == "group-L" || n == "group-R")
    return e.node_kind() == msg::NODE_GROUP && e.side() == (n == "group-L" ? msg::SIDE_L : msg::SIDE_R);
  if (n == "central") return e.node_kind() == msg::NODE_CENTRAL;
  return n == "plant" && e.node_kind() == msg::NODE_PLANT;
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
