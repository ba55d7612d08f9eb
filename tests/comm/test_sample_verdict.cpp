// The verdict run.mcap keeps for each sample (recorder/sample_verdict.hpp): decoded, from the
// process that publishes the topic, within its type's rule and naming its own sender.
#include <gtest/gtest.h>

#include <limits>

#include "comm/dds/dds.hpp"
#include "idl/maptrPubSubTypes.h"
#include "recorder/sample_verdict.hpp"

namespace maptr::recorder {
namespace {

constexpr int kAgents = 16;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <class PubSub, class Msg>
std::string bytes_of(Msg m) {
  PubSub type;
  eprosima::fastrtps::rtps::SerializedPayload_t p(type.getSerializedSizeProvider(&m)());
  EXPECT_TRUE(type.serialize(&m, &p));
  return std::string(reinterpret_cast<const char*>(p.data), p.length);
}

std::string gate(double t) {
  msg::FaultGate g;
  g.tick(3);
  g.t(t);
  return bytes_of<msg::FaultGatePubSubType>(g);
}

std::string reply(int side, uint16_t index, double v) {
  msg::AgentReply r;
  r.tick(7);
  r.side(static_cast<msg::Side>(side));
  r.index(index);
  r.pid(1234);
  r.voltage_V(v);
  r.state(msg::AGENT_ACTIVE);
  return bytes_of<msg::AgentReplyPubSubType>(r);
}

std::string status(int side, std::size_t live) {
  msg::GroupStatus g;
  g.tick(7);
  g.side(static_cast<msg::Side>(side));
  g.active(std::vector<uint8_t>(kAgents / 2, 1));
  g.live(std::vector<uint8_t>(live, 1));
  g.ledger().wear_m(std::vector<double>(kAgents / 2, 2.5));
  g.ledger().active_time_s(std::vector<double>(g.ledger().wear_m().size(), 0.0));
  return bytes_of<msg::GroupStatusPubSubType>(g);
}

std::string ready(const std::string& name) {
  msg::NodeReady r;
  r.name(name);
  r.kind(msg::NODE_AGENT);
  r.pid(99);
  r.ready(true);
  return bytes_of<msg::NodeReadyPubSubType>(r);
}

Verdict judge(const char* topic, const std::string& bytes, const std::string& writer) {
  return judge_sample(topic, bytes, writer, kAgents);
}

TEST(SampleVerdict, TakenOnlyFromTheProcessThatPublishesTheTopic) {
  EXPECT_EQ(judge(comm::topic::kGate, gate(1.0), "plant"), Verdict::kTaken);
  EXPECT_EQ(judge(comm::topic::kGate, gate(1.0), "L3"), Verdict::kForged);
  EXPECT_EQ(judge(comm::topic::kGate, gate(1.0), "launcher"), Verdict::kForged);
  EXPECT_EQ(judge(comm::topic::kGate, gate(1.0), ""), Verdict::kForged)
      << "a writer of no process of the fleet";
  EXPECT_EQ(judge(comm::topic::kAgentReply, reply(0, 3, 5.0), "L3"), Verdict::kTaken);
  EXPECT_EQ(judge(comm::topic::kAgentReply, reply(0, 3, 5.0), "plant"), Verdict::kForged);
  EXPECT_EQ(judge("maptr/unknown", gate(1.0), "plant"), Verdict::kForged);
}

TEST(SampleVerdict, ASampleMustNameItsOwnSender) {
  EXPECT_EQ(judge(comm::topic::kAgentReply, reply(0, 4, 5.0), "L3"), Verdict::kForged)
      << "L3 answering as L4";
  EXPECT_EQ(judge(comm::topic::kAgentReply, reply(1, 3, 5.0), "L3"), Verdict::kForged)
      << "L3 answering as R3";
  EXPECT_EQ(judge(comm::topic::kGroup, status(0, kAgents / 2), "group-L"), Verdict::kTaken);
  EXPECT_EQ(judge(comm::topic::kGroup, status(0, kAgents / 2), "group-R"), Verdict::kForged);
  EXPECT_EQ(judge(comm::topic::kReady, ready("L3"), "L3"), Verdict::kTaken);
  EXPECT_EQ(judge(comm::topic::kReady, ready("plant"), "L3"), Verdict::kForged);
  // The hello is the plant's alone: a member's own ready on it is forged.
  EXPECT_EQ(judge(comm::topic::kHello, ready("plant"), "plant"), Verdict::kTaken);
  EXPECT_EQ(judge(comm::topic::kHello, ready("L3"), "L3"), Verdict::kForged);
  EXPECT_EQ(judge(comm::topic::kHello, ready("plant"), "L3"), Verdict::kForged);
}

TEST(SampleVerdict, TheTypesRuleHolds) {
  EXPECT_EQ(judge(comm::topic::kGate, gate(kNaN), "plant"), Verdict::kMalformed);
  EXPECT_EQ(judge(comm::topic::kAgentReply, reply(0, 3, kNaN), "L3"), Verdict::kMalformed);
  EXPECT_EQ(judge(comm::topic::kAgentReply, reply(0, 999, 5.0), "L3"), Verdict::kMalformed);
  EXPECT_EQ(judge(comm::topic::kGroup, status(0, kAgents / 2 + 1), "group-L"), Verdict::kMalformed);
  msg::CentralCommand c;
  c.v_x_ref(kNaN);
  EXPECT_EQ(judge(comm::topic::kCentral, bytes_of<msg::CentralCommandPubSubType>(c), "central"),
            Verdict::kMalformed);
  c.v_x_ref(0.5);
  EXPECT_EQ(judge(comm::topic::kCentral, bytes_of<msg::CentralCommandPubSubType>(c), "central"),
            Verdict::kTaken);
}

TEST(SampleVerdict, UndecodableWhoeverSentIt) {
  const std::string short_payload("\x00\x01\x00\x00\x01", 5);
  for (const char* topic :
       {comm::topic::kControl, comm::topic::kMembership, comm::topic::kGate, comm::topic::kReady,
        comm::topic::kHello, comm::topic::kTick, comm::topic::kAgentReply, comm::topic::kGroup, comm::topic::kCentral}) {
    EXPECT_EQ(judge(topic, short_payload, ""), Verdict::kUndecodable) << topic;
    EXPECT_EQ(judge(topic, "", "plant"), Verdict::kUndecodable) << topic;
  }
  EXPECT_STREQ(verdict_name(Verdict::kUndecodable), "undecodable");
  EXPECT_STREQ(verdict_name(Verdict::kTaken), "taken");
}

}  // namespace
}  // namespace maptr::recorder
