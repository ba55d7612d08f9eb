#pragma once
// DDS node of the central controller: reads Tick, answers CentralCommand.
#include <spdlog/logger.h>

#include <memory>

#include "central/central_core.hpp"
#include "comm/process.hpp"

namespace maptr::central {

class CentralNode {
 public:
  CentralNode(const comm::ProcessArgs& args, std::shared_ptr<spdlog::logger> log);
  int run();

 private:
  const comm::ProcessArgs& args_;
  std::shared_ptr<spdlog::logger> log_;
  CentralCore core_;
};

}  // namespace maptr::central
