#pragma once
// The outcome of one Level-2 decision of a group controller, as the group reports it (the
// msg::L2_* constants of the DDS messages have the same values; the group node checks it) and
// as the Level-2 log records it (records/level2_log.hpp, column `status`).
#include <cstdint>

namespace maptr::control {

/// kL2None: Level 2 does not run (mode all); kL2Ok: the solver found its optimum;
/// kL2Infeasible: no count holds the reference (or no agent is live), every live agent runs;
/// kL2Failed: the solver reported a failure.
enum Level2Status : uint8_t { kL2None = 0, kL2Ok = 1, kL2Infeasible = 2, kL2Failed = 3 };

}  // namespace maptr::control
