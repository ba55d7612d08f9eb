#pragma once
// The validity rule of every field of every message of idl/maptr.idl, written once: what a
// reader may take without looking further (ranges, finiteness, lengths, known enum values).
// Each taker applies the rule of the type it takes (the plant: plant/validation.hpp, which
// adds the battery's voltage; followers: comm/lockstep/tick_check.hpp; the launcher: NodeReady and
// FaultGate; the plant: MembershipEvent and Control). Free of DDS and of the node.
//
// Fields a rule does not restrict are listed with "any" beside their type below, so that a new
// field is seen to need a rule.
#include <cstddef>

#include "idl/maptr.h"

namespace maptr::msg {

/// Bounds a rule needs that the message does not carry.
struct FleetBounds {
  std::size_t per_side = 0;      ///< agents per side (every mask's length, every count's bound)
  double ref_bound_radps = 1e4;  ///< largest |wheel speed reference|, rad/s
  double v_bound_mps = 1e2;      ///< largest |body speed reference|, m/s
  double w_bound_radps = 1e2;    ///< largest |yaw rate reference|, rad/s
};

/// Longest process name a message may carry (names are L0.., R0.., group-L, group-R, central,
/// plant: far shorter).
inline constexpr std::size_t kMaxNameLength = 64;
/// NodeReady.unmatched: at most this many names (the IDL's bound).
inline constexpr std::size_t kMaxUnmatched = 64;

/// PlantTick: every number finite; battery and applied voltages not negative;
/// active, live and wake one entry of 0 or 1 per agent of a side; n_active and relay_count at
/// most per_side; group stamps and central stamp -1 or more; a known run state;
/// paused empty or one entry per member (2 per_side + 3). Any: tick (ordering is the reader's).
bool well_formed(const PlantTick& t, const FleetBounds& b);
/// AgentReply: a known side, index below per_side, voltage, current and efficiency finite, a
/// known state, pid not 0. Any: tick, rejected. (The voltage's range depends on the driver and
/// the battery: the plant checks it, plant/validation.hpp.)
bool well_formed(const AgentReply& r, const FleetBounds& b);
/// GroupStatus: a known side; active and live one entry of 0 or 1 per agent; wear_m one finite,
/// non-negative distance per agent; n_active, n_live and n_other at most per_side; a known
/// Level-2 status; level2_relaxed finite within [0, per_side]; oracle_n_active -1..per_side;
/// solve_time_ms finite, not negative. Any: tick, decisions, reallocations, rejected.
bool well_formed(const GroupStatus& g, const FleetBounds& b);
/// CentralCommand: v_x_ref, w_ref and both phidot_ref finite and below their bounds; both
/// relay counts at most per_side. Any: tick, segment, rejected.
bool well_formed(const CentralCommand& c, const FleetBounds& b);
/// MembershipEvent: seq above 0; a name of 1..kMaxNameLength characters; a known node kind,
/// side and event kind; an agent's index below per_side; wall_s finite, not negative;
/// participant_id from -1 to 65535.
bool well_formed(const MembershipEvent& e, const FleetBounds& b);
/// Control: a known command other than CONTROL_NONE; seq above 0. Any: tick, member_seq (the
/// fault gate checks they answer its own gate).
bool well_formed(const Control& c);
/// FaultGate: t finite, not negative. Any: tick.
bool well_formed(const FaultGate& g);
/// NodeReady: a name of 1..kMaxNameLength characters, a known kind, pid not 0; unmatched at
/// most kMaxUnmatched names of 1..kMaxNameLength characters, and empty when ready. Any: ready.
bool well_formed(const NodeReady& r);

}  // namespace maptr::msg
