#pragma once
// DDS node of one agent: reads Tick, runs its Level 1 (AgentCore, with the software faults the
// scenario gives it: agent/misbehaviour.hpp), answers AgentReply for the same tick.
#include <spdlog/logger.h>

#include <memory>

#include "agent/misbehaviour.hpp"
#include "comm/dds/process.hpp"

namespace maptr::agent {

class AgentNode {
 public:
  AgentNode(const comm::ProcessArgs& args, int side, int index, std::shared_ptr<spdlog::logger> log);
  /// Runs until the plant finishes the run (0), the plant is lost (3) or a stop signal (0).
  int run();

 private:
  const comm::ProcessArgs& args_;
  int side_, index_;
  std::shared_ptr<spdlog::logger> log_;
  FaultyAgent core_;
};

}  // namespace maptr::agent
