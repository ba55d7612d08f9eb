#pragma once
// DDS node of a group controller: reads Tick, runs GroupCore, answers GroupStatus.
#include <spdlog/logger.h>

#include <memory>

#include "comm/process.hpp"
#include "control/group_core.hpp"

namespace maptr::group {

class GroupNode {
 public:
  GroupNode(const comm::ProcessArgs& args, int side, std::shared_ptr<spdlog::logger> log);
  int run();

 private:
  const comm::ProcessArgs& args_;
  int side_;
  std::shared_ptr<spdlog::logger> log_;
  control::GroupCore core_;
};

}  // namespace maptr::group
