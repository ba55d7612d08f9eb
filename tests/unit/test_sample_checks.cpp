// What a reader checks before it trusts a sample, without DDS: decoding that never throws
// (comm/dds/checked_type.hpp) and the followers' tick check (comm/lockstep/tick_check.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "comm/dds/checked_type.hpp"
#include "comm/lockstep/tick_check.hpp"
#include "idl/maptrPubSubTypes.h"

namespace {

using namespace maptr;
using comm::classify_tick;
using comm::TickVerdict;
using Payload = eprosima::fastrtps::rtps::SerializedPayload_t;

constexpr std::size_t kPerSide = 4;

msg::PlantTick tick(unsigned long long k) {
  msg::PlantTick t;
  t.tick(k);
  for (auto& s : t.sides()) {
    s.battery_V(24.0);
    s.active(std::vector<uint8_t>{1, 1, 0, 0});
    s.live(std::vector<uint8_t>(kPerSide, 1));
    s.wake(std::vector<uint8_t>{1, 1, 0, 0});
    s.n_active(2);
    s.relay_count(2);
  }
  return t;
}

template <class PubSubType, class Sample>
Payload serialized(Sample s) {
  PubSubType type;
  Payload p(type.getSerializedSizeProvider(&s)());
  EXPECT_TRUE(type.serialize(&s, &p));
  return p;
}

TEST(TickCheck, OnlyANewerWellFormedTickIsFollowed) {
  EXPECT_EQ(classify_tick(tick(0), kPerSide, -1), TickVerdict::kNew);
  EXPECT_EQ(classify_tick(tick(8), kPerSide, 7), TickVerdict::kNew);
  EXPECT_EQ(classify_tick(tick(50), kPerSide, 7), TickVerdict::kNew);  // resynchronisation
  EXPECT_EQ(classify_tick(tick(7), kPerSide, 7), TickVerdict::kRepeat);
  EXPECT_EQ(classify_tick(tick(6), kPerSide, 7), TickVerdict::kRejected);
  msg::PlantTick bad = tick(7);
  bad.x(std::nan(""));
  EXPECT_EQ(classify_tick(bad, kPerSide, 7), TickVerdict::kRejected);  // a malformed copy is no repeat
}

TEST(TickCheck, ATickNumberBeyondLongLongIsRejectedNotWrapped) {
  EXPECT_EQ(classify_tick(tick(std::numeric_limits<unsigned long long>::max()), kPerSide, 7),
            TickVerdict::kRejected);
  EXPECT_EQ(classify_tick(tick(1ULL << 63), kPerSide, -1), TickVerdict::kRejected);
}

TEST(TickCheck, CountsAboveASideAndUnknownRunStatesAreMalformed) {
  EXPECT_TRUE(comm::tick_valid(tick(1), kPerSide));
  msg::PlantTick t = tick(1);
  t.sides()[1].n_active(kPerSide + 1);
  EXPECT_FALSE(comm::tick_valid(t, kPerSide));
  t = tick(1);
  t.sides()[0].relay_count(kPerSide + 1);
  EXPECT_FALSE(comm::tick_valid(t, kPerSide));
  t = tick(1);
  t.run_state(static_cast<msg::RunState>(3));
  EXPECT_FALSE(comm::tick_valid(t, kPerSide));
  t.run_state(msg::RUN_ABORTED);
  EXPECT_TRUE(comm::tick_valid(t, kPerSide));
}

TEST(CheckedType, AWellFormedPayloadDecodes) {
  Payload p = serialized<msg::PlantTickPubSubType>(tick(42));
  comm::CheckedType<msg::PlantTickPubSubType> type;
  msg::PlantTick got;
  EXPECT_TRUE(type.deserialize(&p, &got));
  EXPECT_FALSE(comm::last_deserialize_failed());
  EXPECT_EQ(got.tick(), 42u);
  EXPECT_EQ(got.sides()[1].active(), (std::vector<uint8_t>{1, 1, 0, 0}));
}

TEST(CheckedType, APayloadFastCdrThrowsOnIsRefusedNotThrown) {
  // A non-zero first byte of the encapsulation header: the generated code lets fastcdr's
  // BadParamException escape.
  Payload bad_header = serialized<msg::AgentReplyPubSubType>(msg::AgentReply{});
  bad_header.data[0] = 1;
  msg::AgentReplyPubSubType raw;
  msg::AgentReply r;
  EXPECT_ANY_THROW(raw.deserialize(&bad_header, &r));
  comm::CheckedType<msg::AgentReplyPubSubType> checked;
  EXPECT_FALSE(checked.deserialize(&bad_header, &r));
  EXPECT_TRUE(comm::last_deserialize_failed());

  // A boolean of 2 (NodeReady.ready is the payload's last byte).
  msg::NodeReady ready;
  ready.name("L3");
  ready.ready(true);
  Payload two = serialized<msg::NodeReadyPubSubType>(ready);
  two.data[two.length - 1] = 2;
  msg::NodeReady got;
  comm::CheckedType<msg::NodeReadyPubSubType> ready_type;
  EXPECT_FALSE(ready_type.deserialize(&two, &got));
  EXPECT_TRUE(comm::last_deserialize_failed());
}

TEST(CheckedType, ATruncatedPayloadIsRefused) {
  Payload p = serialized<msg::PlantTickPubSubType>(tick(42));
  p.length /= 2;
  comm::CheckedType<msg::PlantTickPubSubType> type;
  msg::PlantTick got;
  EXPECT_FALSE(type.deserialize(&p, &got));
  EXPECT_TRUE(comm::last_deserialize_failed());
}

}  // namespace
