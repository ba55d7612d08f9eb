#pragma once
// DDS node of the plant: the lock-step barrier. Publishes Tick k, waits for every live agent's
// AgentReply k, each live group's GroupStatus k and central's CentralCommand k, integrates,
// and publishes Tick k+1. Membership: the launcher's events (a child died), DDS liveliness
// (a writer's lease expired) and, as a last resort, a per-tick wall-clock deadline that grows
// with the fleet; a member declared dead is re-admitted as soon as it answers the current tick.
#include <spdlog/logger.h>

#include <memory>

#include "comm/process.hpp"

namespace maptr::plant {

class PlantNode {
 public:
  PlantNode(const comm::ProcessArgs& args, std::shared_ptr<spdlog::logger> log);
  int run();

 private:
  const comm::ProcessArgs& args_;
  std::shared_ptr<spdlog::logger> log_;
};

}  // namespace maptr::plant
