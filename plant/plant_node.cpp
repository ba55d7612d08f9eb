#include "plant/plant_node.hpp"

#include "plant/plant_loop.hpp"

namespace maptr::plant {

PlantNode::PlantNode(const comm::ProcessArgs& args, std::shared_ptr<spdlog::logger> log,
                     PlantNodeConfig config)
    : args_(args), log_(std::move(log)), config_(config) {}

int PlantNode::run() {
  auto& stop = comm::stop_flag();
  PlantLoop loop(args_, *log_, config_);
  if (!loop.discover()) return 0;
  // This thread integrates and publishes each tick, and sleeps while the answers come. Under
  // SCHED_FIFO the agents a publish wakes wait for its end instead of preempting it halfway
  // (BENCHMARKS.md); the Fast DDS threads, made before, keep normal scheduling.
  loop.set_scheduling(comm::make_thread_realtime(args_.scenario.plant_priority));
  loop.open_records();
  bool stopped = false;
  while (!stop.load()) {
    const bool last = loop.last_tick();
    if (!last) loop.pass_gate();
    loop.publish(last ? msg::RUN_FINISHED : msg::RUN_RUNNING);
    if (last) break;
    if (!loop.collect()) {
      stopped = true;
      break;
    }
    loop.integrate();
    loop.pace();
  }
  return loop.report(stopped);
}

}  // namespace maptr::plant
