#pragma once
// The group controller's wire adapter: what group `side` reads from a PlantTick for its core, and
// the GroupStatus its decision becomes (no DDS: the generated message
// types only). The group node and the tests that step a core on ticks use this one map.
#include <optional>

#include "control/group_core.hpp"
#include "idl/maptr.h"

namespace maptr::group {

/// What group `side` reads from a tick.
control::GroupInput group_input(const msg::PlantTick& t, int side);

/// The status group `side` answers tick `t` with: decision `d` on input `in`, and its ledger
/// after the step (which the plant keeps for a restart). `rejected` is left to the node.
msg::GroupStatus group_status(const msg::PlantTick& t, int side, const control::GroupInput& in,
                              const control::GroupDecision& d, const control::Ledger& ledger);

/// The ledger a tick carries for the start of group `side` whose DDS participant id is
/// `participant` (comm/dds/fleet_ids.hpp), or for any start of it when the plant was not told
/// which (for_participant < 0), assignment included; nullopt when it carries none.
std::optional<control::Ledger> kept_ledger(const msg::PlantTick& t, int side, long participant);

/// The Level-2 decision a status carries (what the message holds of it: its status, the relaxed
/// optimum, the oracle's count, the solve time, the side's live and the other side's counts).
control::Level2Decision level2_of(const msg::GroupStatus& st);

}  // namespace maptr::group
