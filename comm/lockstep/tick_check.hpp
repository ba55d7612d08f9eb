#pragma once
// What a follower (agent, group, central) checks in a PlantTick from the plant's writer before
// it trusts it, free of DDS: every number finite, the battery and applied voltages not
// negative, one mask entry per agent of a side, counts within the side, a known run state;
// then only a newer tick counts (a jump forward is a resynchronisation after a pause or a
// restart), an exact copy of the last one is no news, anything else is dropped.
#include <cstddef>

#include "idl/maptr.h"

namespace maptr::comm {

/// True when the tick is well-formed for a fleet of per_side agents per side.
bool tick_valid(const msg::PlantTick& t, std::size_t per_side);

enum class TickVerdict {
  kNew,       ///< well-formed and newer than the last tick: follow it
  kRepeat,    ///< well-formed copy of the last tick (resent to a restarted member): ignore
  kRejected,  ///< malformed or older than the last tick: drop and count
};

/// What a follower does with tick t after last_tick (-1 before the first).
TickVerdict classify_tick(const msg::PlantTick& t, std::size_t per_side, long long last_tick);

/// True when agent `index` of `side` must take tick t: the plant waits for its answer (its
/// `wake` bit: assigned, its idle slot or rejoining), or its state may move on other than as an
/// idle agent's (a group or central whose command is not fresh: the agent holds, coasts or
/// stops; the run's end). The tick filter (comm/lockstep/tick_filter.hpp) delivers an agent only these
/// ticks. An agent that skipped ticks k0..k-1 was idle in each with a fresh group and central,
/// so the values of tick k-1 carried in tick k (phidot_prev, phidot_ref_prev) are all it needs
/// to go on (control/level1/agent_core.hpp).
bool tick_wakes_agent(const msg::PlantTick& t, int side, int index);

}  // namespace maptr::comm
