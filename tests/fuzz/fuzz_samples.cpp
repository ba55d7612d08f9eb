// libFuzzer target: a DDS sample's bytes through the path a process takes with it. The type's
// deserialize (fastddsgen code behind comm::CheckedType, as every reader uses it) must refuse
// or decode without throwing; a decoded sample then goes through the checks its reader applies
// before trusting it (the follower's tick check, the plant's sample validation and its fault
// gate, the membership's name lookup). What those checks accept must be safe to use the way the
// processes use it; an escaping exception, a failed invariant (trap) or a sanitizer report is a
// finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "comm/dds/checked_type.hpp"
#include "comm/lockstep/tick_check.hpp"
#include "idl/maptrPubSubTypes.h"
#include "plant/fault_gate.hpp"
#include "plant/membership.hpp"
#include "plant/validation.hpp"
#include "tests/fuzz/sample_input.hpp"

namespace {

using namespace maptr;
using fuzz::kPerSide;

void require(bool ok) {
  if (!ok) __builtin_trap();
}

template <class PubSubType, class Sample>
bool decode(const std::uint8_t* data, std::size_t size, Sample& out) {
  static comm::CheckedType<PubSubType> type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(size));
  if (size > 0) std::memcpy(payload.data, data, size);
  payload.length = static_cast<std::uint32_t>(size);
  const bool ok = type.deserialize(&payload, &out);
  require(ok != comm::last_deserialize_failed());
  return ok;
}

plant::SampleLimits limits() {
  plant::SampleLimits l;
  l.per_side = kPerSide;
  l.battery_V[0] = l.battery_V[1] = fuzz::kBatteryV;
  return l;
}

void tick(const std::uint8_t* d, std::size_t n) {
  msg::PlantTick t;
  if (!decode<msg::PlantTickPubSubType>(d, n, t)) return;
  for (long long last : {-1LL, 0LL, static_cast<long long>(t.tick() >> 1)}) {
    if (comm::classify_tick(t, kPerSide, last) != comm::TickVerdict::kNew) continue;
    // What agents, groups and central read from a tick they follow.
    require(static_cast<long long>(t.tick()) > last);
    for (const msg::SideTick& s : t.sides())
      require(s.active().size() == kPerSide && s.live().size() == kPerSide && s.wake().size() == kPerSide &&
              s.n_active() <= kPerSide &&
              std::isfinite(s.battery_V()) && s.battery_V() >= 0.0);
  }
}

void reply(const std::uint8_t* d, std::size_t n) {
  msg::AgentReply r;
  if (!decode<msg::AgentReplyPubSubType>(d, n, r)) return;
  const plant::SampleLimits l = limits();
  if (plant::check(r, l, static_cast<long long>(r.tick())) != plant::Verdict::kAccepted) return;
  // The plant indexes its per-agent tables by side and index and applies the voltage.
  require(r.side() <= msg::SIDE_R && r.index() < kPerSide);
  require(r.voltage_V() >= 0.0 && r.voltage_V() <= l.battery_V[r.side()] + l.voltage_tolerance_V);
  (void)plant::drives(r);
}

void group(const std::uint8_t* d, std::size_t n) {
  msg::GroupStatus g;
  if (!decode<msg::GroupStatusPubSubType>(d, n, g)) return;
  if (plant::check(g, limits(), static_cast<long long>(g.tick())) != plant::Verdict::kAccepted) return;
  require(g.side() <= msg::SIDE_R && g.active().size() == static_cast<std::size_t>(kPerSide));
}

void central(const std::uint8_t* d, std::size_t n) {
  msg::CentralCommand c;
  if (!decode<msg::CentralCommandPubSubType>(d, n, c)) return;
  const plant::SampleLimits l = limits();
  if (plant::check(c, l, static_cast<long long>(c.tick())) != plant::Verdict::kAccepted) return;
  for (int s = 0; s < 2; ++s)
    require(std::fabs(c.phidot_ref()[s]) < l.ref_bound_radps && c.relay_count_for()[s] <= kPerSide);
}

void membership(const std::uint8_t* d, std::size_t n) {
  msg::MembershipEvent e;
  if (!decode<msg::MembershipEventPubSubType>(d, n, e)) return;
  // The plant applies an event only when it is well-formed and describes the process it names.
  if (!plant::valid(e, limits())) return;
  plant::Membership m(kPerSide, [] { return 0.0; });
  require(m.on_launcher(e.seq(), plant::launcher_event(e.kind()), e.name()));
  require(m.launcher_seq() == e.seq());
  // The same number again is no news, and moves nothing.
  require(!m.on_launcher(e.seq(), plant::launcher_event(e.kind()), e.name()));
  if (const auto id = m.find(e.name()))
    require(plant::member_name(*id) == e.name() || id->role == plant::Role::kAgent);
}

void control(const std::uint8_t* d, std::size_t n) {
  msg::Control c;
  if (!decode<msg::ControlPubSubType>(d, n, c)) return;
  // The plant holding a fault gate at tick 10 after membership event 3.
  plant::FaultGate gate({1.0}, 5.0);
  require(gate.due(1.0));
  gate.hold(10);
  if (c.command() == msg::CONTROL_GATE_OPEN) gate.on_open(c.tick(), c.member_seq());
  require(!gate.released(3) ||
          (c.command() == msg::CONTROL_GATE_OPEN && c.tick() == 10 && c.member_seq() <= 3));
}

template <class PubSubType, class Sample>
void decode_only(const std::uint8_t* d, std::size_t n) {
  Sample s;
  (void)decode<PubSubType>(d, n, s);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const auto kind = static_cast<fuzz::SampleKind>(data[0] % fuzz::kSampleKinds);
  const std::uint8_t* d = data + 1;
  const std::size_t n = size - 1;
  switch (kind) {
    case fuzz::SampleKind::kPlantTick:
      tick(d, n);
      break;
    case fuzz::SampleKind::kAgentReply:
      reply(d, n);
      break;
    case fuzz::SampleKind::kGroupStatus:
      group(d, n);
      break;
    case fuzz::SampleKind::kCentralCommand:
      central(d, n);
      break;
    case fuzz::SampleKind::kMembershipEvent:
      membership(d, n);
      break;
    case fuzz::SampleKind::kControl:
      control(d, n);
      break;
    case fuzz::SampleKind::kFaultGate:
      decode_only<msg::FaultGatePubSubType, msg::FaultGate>(d, n);
      break;
    case fuzz::SampleKind::kNodeReady:
      decode_only<msg::NodeReadyPubSubType, msg::NodeReady>(d, n);
      break;
  }
  return 0;
}
