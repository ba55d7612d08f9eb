#pragma once
// Level-3 wear ledger of one group (side). For every agent j it keeps D_j, the distance the
// agent drove while active [m] (the wear measure the allocation minimises over), and its
// continuous active time [s] (for the thermal limit); with it the group's last decision, so that
// a restarted group controller resumes where it stopped. Over a tick of dt [s] in which the
// side's wheels moved |phidot| r dt [m]:
//   active agent:  D_j += |phidot| r dt,  t_j += dt;     inactive agent:  t_j = 0.
// Its file is records/ledger_file.hpp's.
#include <cstdint>
#include <vector>

namespace maptr::control {

/// Time of an event that has not happened yet, s (finite, so that the JSON file can hold it).
constexpr double kNeverS = -1e300;

struct Ledger {
  std::vector<double> wear_m;         ///< D_j, m driven while active
  std::vector<double> active_time_s;  ///< s, continuous active time
  double last_t = -1.0;               ///< s, time of the last update (< 0: none yet)
  double last_alloc_t = kNeverS;      ///< s, time of the last Level-3 allocation
  int n_target = 0;                   ///< last Level-2 choice (0 = none yet)
  std::vector<uint8_t> assignment;    ///< last assignment (1 = active)
  uint64_t decisions = 0, reallocations = 0;

  /// An empty ledger for per_side agents: no wear, nobody active.
  explicit Ledger(int per_side = 0)
      : wear_m(per_side, 0.0), active_time_s(per_side, 0.0), assignment(per_side, 0) {}

  /// The agents marked in `active` each drove distance_m [m] over dt_s [s]; every other
  /// agent's continuous active time restarts at 0. `active` may be shorter than the ledger
  /// (missing entries count as inactive).
  void accrue(const std::vector<uint8_t>& active, double distance_m, double dt_s);
};

}  // namespace maptr::control
