#pragma once
// The launcher's view of simulated time, taken only from the plant: ticks and fault gates
// count only when their writer belongs to the plant's participant (the GUID prefix the fleet id
// gives the plant: comm/dds/fleet_guid.hpp). A sample from any other participant on maptr/tick or
// maptr/gate (a forgery, or a stale plant) is counted and ignored. Pure: writers are named by
// their GUID prefix.
#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>

namespace maptr::deploy::fleet {

/// The 12-byte GUID prefix of an RTPS participant (shared by all its writers).
using GuidPrefix = std::array<uint8_t, 12>;

/// The last tick the plant published, in the launcher's units.
struct PlantState {
  double t = 0.0;    ///< simulated time, s
  double v_x = 0.0;  ///< body forward speed, m/s
  double energy_J = 0.0;
  int active_L = 0, active_R = 0;
};

class PlantClock {
 public:
  /// The plant's participant (its GUID prefix).
  void learn_plant(const GuidPrefix& p) { plant_ = p; }
  bool knows_plant() const { return plant_.has_value(); }

  /// True if a sample of this writer comes from the plant; counts the others.
  bool from_plant(const GuidPrefix& writer);
  /// A tick: taken if it comes from the plant. Returns whether it was taken.
  bool on_tick(const GuidPrefix& writer, const PlantState& s);
  /// A fault gate at simulated time t: moves the clock forward (never back).
  void on_gate(double t) { state_.t = std::max(state_.t, t); }

  const PlantState& state() const { return state_; }
  long rejected() const { return rejected_; }  ///< samples not from the plant

 private:
  std::optional<GuidPrefix> plant_;
  PlantState state_;
  long rejected_ = 0;
};

}  // namespace maptr::deploy::fleet
