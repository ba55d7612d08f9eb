// Writes the seed corpus of fuzz_samples: well-formed samples of every type the processes read,
// as their writers serialize them, and edge cases the readers must refuse (NaN, a side or an
// index out of range, a voltage above the battery, a mask of another length, a truncated
// payload, a bad encapsulation header, a boolean that is neither 0 nor 1).
//   make_sample_seeds DIR      (tests/fuzz/run.sh --seeds rewrites tests/fuzz/corpus/samples)
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "idl/maptrPubSubTypes.h"
#include "tests/fuzz/sample_input.hpp"

namespace {

using namespace maptr;
using fuzz::SampleKind;
using Bytes = std::vector<std::uint8_t>;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <class PubSubType, class Sample>
Bytes serialize(SampleKind kind, Sample s) {
  PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&s)());
  if (!type.serialize(&s, &payload)) throw std::runtime_error("serialize failed");
  Bytes b{static_cast<std::uint8_t>(kind)};
  b.insert(b.end(), payload.data, payload.data + payload.length);
  return b;
}

msg::PlantTick tick_sample() {
  msg::PlantTick t;
  t.tick(42);
  t.t(0.42);
  t.v_x(9.8);
  for (auto& s : t.sides()) {
    s.battery_V(fuzz::kBatteryV);
    s.V_active(11.5);
    s.phidot(80.0);
    s.phidot_ref(81.0);
    s.active(std::vector<std::uint8_t>(fuzz::kPerSide, 0));
    s.live(std::vector<std::uint8_t>(fuzz::kPerSide, 1));
    s.wake(std::vector<std::uint8_t>(fuzz::kPerSide, 0));
    s.wake()[0] = s.wake()[1] = 1;
    s.active()[0] = s.active()[1] = 1;
    s.n_active(2);
    s.relay_count(2);
  }
  return t;
}

msg::AgentReply reply_sample() {
  msg::AgentReply r;
  r.tick(42);
  r.side(msg::SIDE_R);
  r.index(3);
  r.voltage_V(11.5);
  r.current_A(0.8);
  r.efficiency(0.62);
  r.state(msg::AGENT_ACTIVE);
  return r;
}

msg::GroupStatus group_sample() {
  msg::GroupStatus g;
  g.tick(42);
  g.side(msg::SIDE_L);
  g.active(std::vector<std::uint8_t>(fuzz::kPerSide, 1));
  g.live(std::vector<std::uint8_t>(fuzz::kPerSide, 1));
  g.ledger().wear_m(std::vector<double>(fuzz::kPerSide, 1.5));
  g.ledger().active_time_s(std::vector<double>(g.ledger().wear_m().size(), 0.0));
  g.n_active(fuzz::kPerSide);
  g.level2_status(msg::L2_OK);
  return g;
}

msg::CentralCommand central_sample() {
  msg::CentralCommand c;
  c.tick(42);
  c.v_x_ref(10.0);
  c.phidot_ref({80.0, 82.0});
  c.relay_count_for({2, 3});
  return c;
}

msg::MembershipEvent member_sample(const std::string& name, msg::MemberEvent kind) {
  msg::MembershipEvent e;
  e.seq(3);
  e.name(name);
  e.node_kind(msg::NODE_AGENT);
  e.index(5);
  e.kind(kind);
  return e;
}

msg::Control control_sample(msg::ControlCommand cmd, std::uint64_t tick, std::uint64_t member_seq) {
  msg::Control c;
  c.command(cmd);
  c.seq(1);
  c.tick(tick);
  c.member_seq(member_seq);
  return c;
}

using Seeds = std::vector<std::pair<std::string, Bytes>>;

void tick_seeds(Seeds& out) {
  const auto k = SampleKind::kPlantTick;
  out.push_back({"tick-ok", serialize<msg::PlantTickPubSubType>(k, tick_sample())});
  msg::PlantTick t = tick_sample();
  t.run_state(msg::RUN_FINISHED);
  out.push_back({"tick-finished", serialize<msg::PlantTickPubSubType>(k, t)});
  t = tick_sample();
  t.sides()[1].phidot_ref(kNaN);
  out.push_back({"tick-nan", serialize<msg::PlantTickPubSubType>(k, t)});
  t = tick_sample();
  t.sides()[0].active(std::vector<std::uint8_t>(3 * fuzz::kPerSide, 1));
  out.push_back({"tick-long-mask", serialize<msg::PlantTickPubSubType>(k, t)});
  t = tick_sample();
  t.tick(std::numeric_limits<std::uint64_t>::max());
  out.push_back({"tick-far-future", serialize<msg::PlantTickPubSubType>(k, t)});
  // With the drive's measurements (fault detection on), and with a NaN current among them.
  t = tick_sample();
  for (auto& s : t.sides()) {
    s.drove(std::vector<std::uint8_t>(fuzz::kPerSide, 1));
    s.drive_V(std::vector<float>(fuzz::kPerSide, 11.5f));
    s.measured_A(std::vector<float>(fuzz::kPerSide, 0.8f));
    s.reported(std::vector<std::uint8_t>(fuzz::kPerSide, 1));
    s.reported_A(std::vector<float>(fuzz::kPerSide, 0.8f));
  }
  out.push_back({"tick-measured", serialize<msg::PlantTickPubSubType>(k, t)});
  t.sides()[1].measured_A()[2] = std::numeric_limits<float>::quiet_NaN();
  out.push_back({"tick-measured-nan", serialize<msg::PlantTickPubSubType>(k, t)});
  // Handing a restarted group-R its kept wear ledger, and the same with a negative distance.
  t = tick_sample();
  msg::KeptLedger kept;
  kept.side(msg::SIDE_R);
  kept.for_participant(5 + 2 * fuzz::kPerSide + 6);
  kept.assignment(std::vector<std::uint8_t>(fuzz::kPerSide, 1));
  kept.ledger().wear_m(std::vector<double>(fuzz::kPerSide, 2.5));
  kept.ledger().active_time_s(std::vector<double>(fuzz::kPerSide, 0.5));
  kept.ledger().last_t(12.0);
  kept.ledger().last_alloc_t(10.0);
  t.ledgers().push_back(kept);
  out.push_back({"tick-kept-ledger", serialize<msg::PlantTickPubSubType>(k, t)});
  t.ledgers()[0].ledger().wear_m()[1] = -1.0;
  out.push_back({"tick-kept-ledger-negative", serialize<msg::PlantTickPubSubType>(k, t)});
}

void reply_seeds(Seeds& out) {
  const auto k = SampleKind::kAgentReply;
  out.push_back({"reply-ok", serialize<msg::AgentReplyPubSubType>(k, reply_sample())});
  msg::AgentReply r = reply_sample();
  r.voltage_V(1000.0);
  out.push_back({"reply-1000V", serialize<msg::AgentReplyPubSubType>(k, r)});
  r = reply_sample();
  r.side(static_cast<msg::Side>(7));
  out.push_back({"reply-side-7", serialize<msg::AgentReplyPubSubType>(k, r)});
  r = reply_sample();
  r.index(60000);
  out.push_back({"reply-index-60000", serialize<msg::AgentReplyPubSubType>(k, r)});
  r = reply_sample();
  r.current_A(kNaN);
  out.push_back({"reply-nan", serialize<msg::AgentReplyPubSubType>(k, r)});
  Bytes cut = serialize<msg::AgentReplyPubSubType>(k, reply_sample());
  cut.resize(cut.size() / 2);
  out.push_back({"reply-truncated", cut});
  Bytes bad_header = serialize<msg::AgentReplyPubSubType>(k, reply_sample());
  bad_header[1] = 1;  // the encapsulation's first byte must be 0
  out.push_back({"reply-bad-encapsulation", bad_header});
}

void other_seeds(Seeds& out) {
  out.push_back(
      {"group-ok", serialize<msg::GroupStatusPubSubType>(SampleKind::kGroupStatus, group_sample())});
  msg::GroupStatus g = group_sample();
  g.active(std::vector<std::uint8_t>(2, 1));
  out.push_back({"group-short-mask", serialize<msg::GroupStatusPubSubType>(SampleKind::kGroupStatus, g)});
  g = group_sample();
  g.faulty(std::vector<std::uint8_t>(fuzz::kPerSide, 0));
  g.faulty()[1] = msg::DIAG_SHORT;
  out.push_back({"group-faulty", serialize<msg::GroupStatusPubSubType>(SampleKind::kGroupStatus, g)});
  out.push_back({"central-ok",
                 serialize<msg::CentralCommandPubSubType>(SampleKind::kCentralCommand, central_sample())});
  msg::CentralCommand c = central_sample();
  c.phidot_ref({std::numeric_limits<double>::infinity(), 0.0});
  out.push_back({"central-inf", serialize<msg::CentralCommandPubSubType>(SampleKind::kCentralCommand, c)});
  for (const char* name : {"L3", "group-R", "central", "R99", "L01"})
    out.push_back({std::string("member-") + name,
                   serialize<msg::MembershipEventPubSubType>(SampleKind::kMembershipEvent,
                                                             member_sample(name, msg::MEMBER_DIED))});
  out.push_back({"control-start", serialize<msg::ControlPubSubType>(
                                      SampleKind::kControl, control_sample(msg::CONTROL_START, 0, 0))});
  out.push_back(
      {"control-gate-open", serialize<msg::ControlPubSubType>(
                                SampleKind::kControl, control_sample(msg::CONTROL_GATE_OPEN, 10, 3))});
  msg::FaultGate gate;
  gate.tick(10);
  gate.t(1.0);
  out.push_back({"gate-ok", serialize<msg::FaultGatePubSubType>(SampleKind::kFaultGate, gate)});
  msg::NodeReady ready;
  ready.name("L3");
  ready.ready(true);
  Bytes r = serialize<msg::NodeReadyPubSubType>(SampleKind::kNodeReady, ready);
  out.push_back({"ready-ok", r});
  r.back() = 2;  // `ready`, the last byte: a boolean is 0 or 1
  out.push_back({"ready-bool-2", r});
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_sample_seeds DIR\n");
    return 2;
  }
  Seeds seeds;
  tick_seeds(seeds);
  reply_seeds(seeds);
  other_seeds(seeds);
  for (const auto& [name, bytes] : seeds) {
    std::ofstream f(std::string(argv[1]) + "/" + name, std::ios::binary);
    f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!f) {
      std::fprintf(stderr, "make_sample_seeds: cannot write %s/%s\n", argv[1], name.c_str());
      return 1;
    }
  }
  std::printf("%zu seeds in %s\n", seeds.size(), argv[1]);
  return 0;
}
