#pragma once
// One Level-2 decision of a group controller, once: the group core fills it, the status message
// carries it (group/group_wire.cpp; the msg::L2_* constants have the same values, checked at
// compile time there), the Level-2 log is its rows (records/level2_log.hpp) and `maptr top`
// shows it.
#include <cstdint>

namespace maptr::control {

/// kL2None: Level 2 does not run (mode all); kL2Ok: the solver found its optimum;
/// kL2Infeasible: no count holds the reference (or no agent is live), every live agent runs;
/// kL2Failed: the solver reported a failure.
enum Level2Status : uint8_t { kL2None = 0, kL2Ok = 1, kL2Infeasible = 2, kL2Failed = 3 };

/// "none", "ok", "infeasible", "failed"; "?" for a code that is none of them.
inline const char* level2_status_name(uint8_t s) {
  switch (s) {
    case kL2None:
      return "none";
    case kL2Ok:
      return "ok";
    case kL2Infeasible:
      return "infeasible";
    case kL2Failed:
      return "failed";
    default:
      return "?";
  }
}

struct Level2Decision {
  double t_s = 0.0;          ///< s, time of the tick whose inputs the decision used
  int n_live = 0;            ///< live agents of the side when it was applied
  int n_other = 0;           ///< the other side's active count in its inputs
  uint8_t status = kL2None;  ///< a Level2Status
  double relaxed = 0.0;      ///< the solver's relaxed (continuous) optimum N_a
  int ipopt_n_active = -1;   ///< the solver's integer choice (before the feasibility fallback)
  int oracle_n_active = -1;  ///< the exhaustive search's N_a (-1: not run)
  int n_target = 0;          ///< the N_a the side runs from it
  double solve_ms = 0.0;     ///< ms, the solver's wall clock (diagnostics only)
};

}  // namespace maptr::control
