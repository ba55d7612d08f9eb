#pragma once
// DDS node of the plant: the lock-step barrier. Publishes Tick k, waits for every live agent's
// AgentReply k, each live group's GroupStatus k and central's CentralCommand k, integrates,
// and publishes Tick k+1. The protocol's parts are objects of their own (membership, barrier,
// sample validation, fault gate, report; the physics in plant_core::PlantCore): this node only wires
// the DDS inboxes and writers to them.
#include <spdlog/logger.h>

#include <memory>

#include "comm/dds/process.hpp"
#include "plant/plant_config.hpp"

namespace maptr::plant {

class PlantNode {
 public:
  PlantNode(const comm::ProcessArgs& args, std::shared_ptr<spdlog::logger> log, PlantNodeConfig config = {});
  /// Discovery, then per tick: fault gate, publish, collect, integrate, pace; then the report.
  int run();

 private:
  const comm::ProcessArgs& args_;
  std::shared_ptr<spdlog::logger> log_;
  PlantNodeConfig config_;
};

}  // namespace maptr::plant
