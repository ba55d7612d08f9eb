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

}  // namespace maptr::comm
