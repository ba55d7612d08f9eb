#pragma once
// The input format of the fuzz_samples target, shared with the program that writes its seed
// corpus: one byte naming the sample's type (its index in SampleKind, modulo kSampleKinds),
// then the serialized payload exactly as a DataReader hands it to the type's deserialize (the
// 4-byte CDR encapsulation header, then the CDR body).
#include <cstddef>
#include <cstdint>

namespace maptr::fuzz {

enum class SampleKind : std::uint8_t {
  kPlantTick,
  kAgentReply,
  kGroupStatus,
  kCentralCommand,
  kMembershipEvent,
  kControl,
  kFaultGate,
  kNodeReady,
};
inline constexpr int kSampleKinds = 8;

/// The fleet the samples are checked against: agents per side, battery voltages, V.
inline constexpr int kPerSide = 8;
inline constexpr double kBatteryV = 23.4;

}  // namespace maptr::fuzz
