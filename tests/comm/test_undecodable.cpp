// Samples whose payload does not deserialize (comm::CheckedType refuses them): with Fast DDS
// 2.9.1, DataReader::take_next_sample answers NO_DATA for such a sample, so a reader's Inbox
// must count it from the refusal itself and go on taking what follows. A raw writer (the
// recorder's and the replayer's type, comm/dds/raw_type.hpp) sends bytes no reader can decode.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "comm/dds/dds.hpp"
#include "comm/dds/raw_type.hpp"
#include "idl/maptrPubSubTypes.h"

namespace maptr::comm {
namespace {

/// A CDR little-endian encapsulation header and a body.
std::string payload(const std::string& body) { return std::string("\x00\x01\x00\x00", 4) + body; }

/// A serialized FaultGate (tick, t).
std::string gate_bytes(uint64_t tick, double t) {
  msg::FaultGatePubSubType type;
  msg::FaultGate g;
  g.tick(tick);
  g.t(t);
  eprosima::fastrtps::rtps::SerializedPayload_t p(type.getSerializedSizeProvider(&g)());
  EXPECT_TRUE(type.serialize(&g, &p));
  return std::string(reinterpret_cast<const char*>(p.data), p.length);
}

template <class Pred>
bool wait_until(Pred p, double s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(s);
  while (!p()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

DdsOptions options() {
  DdsOptions o;
  o.domain = 100 + static_cast<int>(getpid() % 100);
  o.shm = false;  // UDP on loopback: no shared-memory files left by a failed test
  return o;
}

TEST(Undecodable, EveryRefusedSampleIsCountedAndTheNextOnesAreTaken) {
  Signal signal;
  Inbox<msg::FaultGate> inbox(signal);
  MatchCounter matched;
  Participant reader_p("reader", options());
  reader_p.reader(reader_p.topic<msg::FaultGatePubSubType>(topic::kGate), Profile::kLatched, &inbox);
  Participant writer_p("raw-writer", options());
  auto* w = writer_p.writer(writer_p.topic(topic::kGate, new RawType("maptr::msg::FaultGate", 64)),
                            Profile::kLatched, &matched);
  ASSERT_TRUE(wait_until([&] { return matched.matched() > 0 && inbox.matched() > 0; }, 20));
  // Too short for its fields, a bad encapsulation header, then a good gate; three times over.
  constexpr int kRounds = 3;
  for (int i = 0; i < kRounds; ++i) {
    RawSample s;
    s.bytes = payload("\x01\x02");
    ASSERT_TRUE(w->write(&s));
    s.bytes = std::string("\x7f\x7f\x00\x00", 4) + gate_bytes(7, 1.0).substr(4);
    ASSERT_TRUE(w->write(&s));
    s.bytes = gate_bytes(100 + i, 2.5);
    ASSERT_TRUE(w->write(&s));
  }
  std::vector<uint64_t> taken;
  ASSERT_TRUE(wait_until(
      [&] {
        for (auto& [g, h] : inbox.drain()) taken.push_back(g.tick());
        return taken.size() >= kRounds && inbox.undecodable() >= 2 * kRounds;
      },
      20))
      << "taken " << taken.size() << ", undecodable " << inbox.undecodable();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // nothing more comes
  for (auto& [g, h] : inbox.drain()) taken.push_back(g.tick());
  EXPECT_EQ(taken, (std::vector<uint64_t>{100, 101, 102}));
  EXPECT_EQ(inbox.undecodable(), 2u * kRounds);
}

}  // namespace
}  // namespace maptr::comm
