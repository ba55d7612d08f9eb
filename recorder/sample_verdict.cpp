#include "recorder/sample_verdict.hpp"

#include "comm/dds/checked_type.hpp"
#include "comm/dds/raw_type.hpp"
#include "config/scenario.hpp"
#include "idl/maptrPubSubTypes.h"
#include "idl/rules.hpp"

namespace maptr::recorder {

namespace {
/// In the order the fleet's readers judge: the sample must decode as `Generated`'s message,
/// come from a process that publishes `topic`, hold the type's `rule` and state its sender's
/// identity (`own`).
template <class Generated, class Message, class Rule, class Own>
Verdict check(const std::string& bytes, const std::string& topic, const std::string& writer, Rule rule,
              Own own) {
  Message m;
  if (!comm::decode<Generated>(bytes, m)) return Verdict::kUndecodable;
  if (writer.empty() || !comm::publishes(writer, topic)) return Verdict::kForged;
  if (!rule(m)) return Verdict::kMalformed;
  return own(m) ? Verdict::kTaken : Verdict::kForged;
}

/// Whether an agent `writer` is the agent at `side`, `index`.
bool is_agent(const std::string& writer, int side, int index) {
  int s = 0, i = 0;
  return config::parse_agent_name(writer, s, i) && s == side && i == index;
}

bool is_group(const std::string& writer, int side) { return writer == (side == 0 ? "group-L" : "group-R"); }
}  // namespace

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::kTaken:
      return "taken";
    case Verdict::kForged:
      return "forged";
    case Verdict::kUndecodable:
      return "undecodable";
    case Verdict::kMalformed:
      return "malformed";
  }
  return "?";
}

Verdict judge_sample(const std::string& topic, const std::string& bytes, const std::string& writer,
                     int agents) {
  namespace t = comm::topic;
  msg::FleetBounds b;
  b.per_side = static_cast<std::size_t>(agents / 2);
  const auto any = [](const auto&) { return true; };
  if (topic == t::kTick)
    return check<msg::PlantTickPubSubType, msg::PlantTick>(
        bytes, topic, writer, [&](const auto& m) { return well_formed(m, b); }, any);
  if (topic == t::kAgentReply)
    return check<msg::AgentReplyPubSubType, msg::AgentReply>(
        bytes, topic, writer, [&](const auto& m) { return well_formed(m, b); },
        [&](const auto& m) { return is_agent(writer, static_cast<int>(m.side()), m.index()); });
  if (topic == t::kGroup)
    return check<msg::GroupStatusPubSubType, msg::GroupStatus>(
        bytes, topic, writer, [&](const auto& m) { return well_formed(m, b); },
        [&](const auto& m) { return is_group(writer, static_cast<int>(m.side())); });
  if (topic == t::kCentral)
    return check<msg::CentralCommandPubSubType, msg::CentralCommand>(
        bytes, topic, writer, [&](const auto& m) { return well_formed(m, b); }, any);
  if (topic == t::kMembership)
    return check<msg::MembershipEventPubSubType, msg::MembershipEvent>(
        bytes, topic, writer, [&](const auto& m) { return well_formed(m, b); }, any);
  if (topic == t::kControl)
    return check<msg::ControlPubSubType, msg::Control>(
        bytes, topic, writer, [](const auto& m) { return well_formed(m); }, any);
  if (topic == t::kGate)
    return check<msg::FaultGatePubSubType, msg::FaultGate>(
        bytes, topic, writer, [](const auto& m) { return well_formed(m); }, any);
  if (topic == t::kHello)  // the plant's NodeReady again, to the members (comm/dds/dds.hpp)
    return check<msg::NodeReadyPubSubType, msg::NodeReady>(
        bytes, topic, writer, [](const auto& m) { return well_formed(m); },
        [&](const auto& m) { return writer == "plant" && m.name() == writer; });
  if (topic == t::kReady)
    return check<msg::NodeReadyPubSubType, msg::NodeReady>(
        bytes, topic, writer, [](const auto& m) { return well_formed(m); },
        [&](const auto& m) { return m.name() == writer; });
  return Verdict::kForged;
}

}  // namespace maptr::recorder
