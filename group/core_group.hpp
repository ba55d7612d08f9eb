#pragma once
// Group controller logic (one per side), free of DDS: decides which of its agents run.
//   mode "all" (the paper's NO): every live agent active.
//   mode "ec": Level 2 every level2_period_s (how many, Ipopt on the relaxed problem), Level 3
//     (which: model::allocate on the wear ledger) every T_ON, whenever N_a changes, whenever an
//     active agent fails or reaches the thermal limit. While the robot is still far from its
//     reference speed (start, after a fault) every live agent runs: Level 2 is a cruise decision.
// The wear ledger (distance each agent drove while active, and its continuous active time) is
// saved after every decision and at exit, and loaded at start: a restarted controller resumes it.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "group/core_level2.hpp"

namespace maptr::group {

/// What the group reads from one tick.
struct GroupInput {
  long long tick = 0;
  double t = 0.0;                    ///< s
  double v_x = 0.0, w = 0.0;         ///< body state at t
  double phidot_side = 0.0;          ///< rad/s, this side's wheels
  double phidot_ref_L = 0.0, phidot_ref_R = 0.0;  ///< rad/s, references in force
  double battery_V = 0.0;            ///< V, this side
  std::vector<uint8_t> live;         ///< membership of this side (from the plant)
  std::vector<uint8_t> active;       ///< assignment that was in force over [t_{k-1}, t_k]
  int n_other = 0;                   ///< other side's active count, relayed by central
};

struct GroupDecision {
  std::vector<uint8_t> active;       ///< assignment from tick k+1
  int n_active = 0, n_live = 0;
  uint8_t level2_status = 0;         ///< msg::L2_* values
  double level2_relaxed = 0.0;
  int oracle_n_active = -1;
  double solve_time_ms = 0.0;
  bool level2_ran = false;           ///< a Level-2 decision was taken at this tick
  int ipopt_n_active = -1;           ///< the integer Ipopt's relaxed optimum led to (before feasibility)
  uint64_t decisions = 0, reallocations = 0;
};

struct Ledger {
  std::vector<double> wear_m;        ///< m, distance driven while active
  std::vector<double> active_time_s; ///< s, continuous active time
  double last_t = -1.0;              ///< s, time of the last update
  double last_alloc_t = -1e300;      ///< s, time of the last Level-3 allocation
  int n_target = 0;                  ///< last Level-2 choice (0 = none yet)
  std::vector<uint8_t> assignment;   ///< last assignment
  uint64_t decisions = 0, reallocations = 0;

  /// JSON file I/O; load returns false if the file does not exist; throws on a corrupt file.
  bool load(const std::string& path, int per_side);
  void save(const std::string& path) const;   ///< atomic (write + rename)
};

class GroupCore {
 public:
  GroupCore(int side, const config::Scenario& s, std::string ledger_path);
  GroupDecision step(const GroupInput& in);
  const Ledger& ledger() const { return ledger_; }
  bool resumed() const { return resumed_; }
  void save() const;

 private:
  int side_;
  config::Scenario s_;
  std::string ledger_path_;
  Ledger ledger_;
  Level2Solver solver_;
  bool resumed_ = false;
  double last_l2_t_ = -1e300;
  bool cruise_ = false;
  GroupDecision last_;
};

}  // namespace maptr::group
