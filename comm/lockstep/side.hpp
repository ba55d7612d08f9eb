#pragma once
// Sides on the wire: the DDS-free parts of the project number the sides 0 (left) and 1
// (right); the messages carry msg::Side and index per-side arrays with it.
#include "idl/maptr.h"

namespace maptr::comm {

static_assert(msg::SIDE_L == 0 && msg::SIDE_R == 1, "sides index the per-side arrays: 0 = L, 1 = R");

/// The message's side for side number s (0 = left, 1 = right).
inline msg::Side to_msg_side(int s) { return static_cast<msg::Side>(s); }

}  // namespace maptr::comm
