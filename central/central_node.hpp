#pragma once
// DDS node of the central controller: reads Tick, answers CentralCommand.
#include <spdlog/logger.h>

#include <memory>

#include "comm/dds/process.hpp"
#include "control/central_core.hpp"

namespace maptr::central {

class CentralNode {
 public:
  CentralNode(const comm::ProcessArgs& args, std::shared_ptr<spdlog::logger> log);
  int run();

 private:
  const comm::ProcessArgs& args_;
  std::shared_ptr<spdlog::logger> log_;
  control::CentralCore core_;
};

}  // namespace maptr::central
