#pragma once
// DDS node of a group controller: reads Tick, runs GroupCore, answers GroupStatus. Level 2
// runs on the node's worker thread (Level2Worker), off the tick's path.
#include <spdlog/logger.h>

#include <memory>

#include "comm/dds/process.hpp"
#include "control/group_core.hpp"
#include "group/level2_worker.hpp"
#include "idl/maptr.h"

namespace maptr::group {

/// A pause after each Level-2 solve for the group nodes this process creates from now on: a
/// slow solver, to show that how long a solve takes cannot change a run. A seam for the tests'
/// hooked binaries (tests/hooks); the product sets none.
void set_level2_pause(std::chrono::milliseconds pause);

class GroupNode {
 public:
  GroupNode(const comm::ProcessArgs& args, int side, std::shared_ptr<spdlog::logger> log);
  int run();

 private:
  const comm::ProcessArgs& args_;
  int side_;
  std::shared_ptr<spdlog::logger> log_;
  Level2Worker worker_;
  control::GroupCore core_;
  bool infeasible_ = false;  ///< Level 2's last decision was infeasible (logged once per change)

  /// Goes on from the ledger the plant kept when tick `t` (the first this start sees) carries one.
  void resume_from(const msg::PlantTick& t);
  /// Logs what changed at this step: Level 2's feasibility, agents isolated or let back.
  void report(const control::GroupInput& in, const control::GroupDecision& d);
};

}  // namespace maptr::group
