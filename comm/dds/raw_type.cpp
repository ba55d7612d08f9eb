#include "comm/dds/raw_type.hpp"

#include <cstring>

#include "config/scenario.hpp"
#include "idl/maptrPubSubTypes.h"

namespace maptr::comm {

namespace rtps = eprosima::fastrtps::rtps;

RawType::RawType(const std::string& type_name, uint32_t max_size) {
  setName(type_name.c_str());
  m_typeSize = max_size;
  m_isGetKeyDefined = false;  // MAPTR's types have no key
  auto_fill_type_object(false);
  auto_fill_type_information(false);
}

bool RawType::serialize(void* data, rtps::SerializedPayload_t* payload) {
  const auto& s = static_cast<RawSample*>(data)->bytes;
  if (s.size() < 4 || s.size() > payload->max_size) return false;
  std::memcpy(payload->data, s.data(), s.size());
  payload->length = static_cast<uint32_t>(s.size());
  payload->encapsulation = s[1] == 0 ? CDR_BE : CDR_LE;  // the header's second byte: 0 big, 1 little
  return true;
}

bool RawType::deserialize(rtps::SerializedPayload_t* payload, void* data) {
  static_cast<RawSample*>(data)->bytes.assign(reinterpret_cast<const char*>(payload->data), payload->length);
  return true;
}

std::function<uint32_t()> RawType::getSerializedSizeProvider(void* data) {
  return [data] { return static_cast<uint32_t>(static_cast<RawSample*>(data)->bytes.size()); };
}

void* RawType::createData() { return new RawSample(); }

void RawType::deleteData(void* data) { delete static_cast<RawSample*>(data); }

bool RawType::getKey(void*, rtps::InstanceHandle_t*, bool) { return false; }

namespace {

template <class PubSubType>
FleetTopic make(const char* topic, Profile p, bool from_plant) {
  PubSubType t;
  return {topic, t.getName(), t.m_typeSize, p, from_plant};
}

}  // namespace

const std::vector<FleetTopic>& fleet_topics() {
  static const std::vector<FleetTopic> all = {
      make<msg::PlantTickPubSubType>(topic::kTick, Profile::kStream, true),
      make<msg::AgentReplyPubSubType>(topic::kAgentReply, Profile::kStream, false),
      make<msg::GroupStatusPubSubType>(topic::kGroup, Profile::kStream, false),
      make<msg::CentralCommandPubSubType>(topic::kCentral, Profile::kStream, false),
      make<msg::MembershipEventPubSubType>(topic::kMembership, Profile::kLatched, false),
      make<msg::ControlPubSubType>(topic::kControl, Profile::kLatched, false),
      make<msg::NodeReadyPubSubType>(topic::kReady, Profile::kLatched, false),
      make<msg::FaultGatePubSubType>(topic::kGate, Profile::kLatched, true),
      make<msg::NodeReadyPubSubType>(topic::kHello, Profile::kStream, true),
  };
  return all;
}

const FleetTopic* find_fleet_topic(const std::string& name) {
  for (const auto& t : fleet_topics())
    if (t.topic == name) return &t;
  return nullptr;
}

std::vector<std::string> published_topics(const std::string& name) {
  int side = 0, index = 0;
  if (name == "plant") return {topic::kTick, topic::kGate, topic::kReady, topic::kHello};
  if (name == "central") return {topic::kCentral, topic::kReady};
  if (name == "group-L" || name == "group-R") return {topic::kGroup, topic::kReady};
  if (name == "launcher") return {topic::kMembership, topic::kControl};
  if (config::parse_agent_name(name, side, index)) return {topic::kAgentReply, topic::kReady};
  return {};
}

bool publishes(const std::string& name, const std::string& topic) {
  for (const auto& t : published_topics(name))
    if (t == topic) return true;
  return false;
}

}  // namespace maptr::comm
