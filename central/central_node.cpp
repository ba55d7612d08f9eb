#include "central/central_node.hpp"

#include <unistd.h>

#include <cmath>

#include "idl/maptrPubSubTypes.h"

namespace maptr::central {

CentralNode::CentralNode(const comm::ProcessArgs& args, std::shared_ptr<spdlog::logger> log)
    : args_(args), log_(std::move(log)), core_(args.scenario) {}

int CentralNode::run() {
  auto& stop = comm::stop_flag();
  comm::Signal signal;
  comm::Inbox<msg::PlantTick> ticks(signal);
  comm::MatchCounter cmd_match(&signal);
  comm::Participant p(args_.name, args_.dds);
  auto* t_tick = p.topic<msg::PlantTickPubSubType>(comm::topic::kTick);
  auto* t_cmd = p.topic<msg::CentralCommandPubSubType>(comm::topic::kCentral);
  auto* t_ready = p.topic<msg::NodeReadyPubSubType>(comm::topic::kReady);
  p.reader(t_tick, comm::Profile::kStream, &ticks);
  auto* w_cmd = p.writer(t_cmd, comm::Profile::kStream, &cmd_match);
  auto* w_ready = p.writer(t_ready, comm::Profile::kLatched);

  bool announced = false;
  comm::PlantWatch plant;
  long long last_tick = -1;
  uint64_t rejected = 0;
  uint64_t seen = signal.count();
  while (!stop.load()) {
    seen = signal.wait_until(seen, std::chrono::steady_clock::now() + std::chrono::milliseconds(200));
    if (!announced && ticks.matched() >= 1 && cmd_match.matched() >= 1) {
      comm::announce_ready(w_ready, args_.name, msg::NODE_CENTRAL);
      announced = true;
      log_->info("matched the plant: ready");
    }
    if (plant.lost(ticks.drain_liveliness())) {
      log_->error("lost the plant (liveliness): exiting");
      return 3;
    }
    for (auto& [t, handle] : ticks.drain()) {
      if (!std::isfinite(t.t()) || static_cast<long long>(t.tick()) <= last_tick) {
        ++rejected;
        log_->warn("rejected malformed or stale tick {} ({} so far)", t.tick(), rejected);
        continue;
      }
      last_tick = static_cast<long long>(t.tick());
      if (t.run_state() != msg::RUN_RUNNING) {
        log_->info("run ended at tick {}: exiting", last_tick);
        return 0;
      }
      const CentralOutput o = core_.step(t.t(), t.n_active_L(), t.n_active_R());
      msg::CentralCommand c;
      c.tick(t.tick());
      c.v_x_ref(o.v_x_ref);
      c.w_ref(o.w_ref);
      c.phidot_ref_L(o.phidot_ref_L);
      c.phidot_ref_R(o.phidot_ref_R);
      c.relay_count_for_L(static_cast<uint16_t>(o.relay_for_L));
      c.relay_count_for_R(static_cast<uint16_t>(o.relay_for_R));
      c.segment(static_cast<uint16_t>(o.segment));
      c.rejected(rejected);
      w_cmd->write(&c);
    }
  }
  return 0;
}

}  // namespace maptr::central
