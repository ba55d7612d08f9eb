#pragma once
// DDS node of a group controller: reads Tick, runs GroupCore, answers GroupStatus. Level 2
// runs on the node's worker thread (Level2Worker), off the tick's path.
#include <spdlog/logger.h>

#include <memory>

#include "comm/process.hpp"
#include "control/group_core.hpp"
#include "group/level2_worker.hpp"

namespace maptr::group {

/// Test-only: a pause after each Level-2 solve, ms, from this environment variable (unset: none).
inline constexpr const char* kTestLevel2DelayEnv = "MAPTR_TEST_LEVEL2_DELAY_MS";
/// The longest such pause accepted, ms.
inline constexpr long kMaxTestLevel2DelayMs = 10000;

/// The pause MAPTR_TEST_LEVEL2_DELAY_MS asks for; throws std::invalid_argument naming the
/// variable and its value if it is not an integer in [0, kMaxTestLevel2DelayMs].
std::chrono::milliseconds test_level2_delay();

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
};

}  // namespace maptr::group
