#pragma once
// The group controller's wire adapter: what group `side` reads from a PlantTick for its core, and
// the GroupStatus its decision becomes (no DDS: the generated message
// types only). The group node and the tests that step a core on ticks use this one map.
#include "control/group_core.hpp"
#include "idl/maptr.h"

namespace maptr::group {

/// What group `side` reads from a tick.
control::GroupInput group_input(const msg::PlantTick& t, int side);

/// The status group `side` answers tick `t` with: decision `d` on input `in`, and the ledger's
/// wear. `rejected` is left to the node.
msg::GroupStatus group_status(const msg::PlantTick& t, int side, const control::GroupInput& in,
                              const control::GroupDecision& d, const control::Ledger& ledger);

}  // namespace maptr::group
