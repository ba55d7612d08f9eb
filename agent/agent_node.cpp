#include "agent/agent_node.hpp"

#include <unistd.h>

#include <cmath>

#include "idl/maptrPubSubTypes.h"

namespace maptr::agent {

namespace {
AgentConfig make_config(const config::Scenario& s) {
  AgentConfig c;
  c.motor = s.robot.motor;
  c.pid = s.control.pid;
  c.wheel_radius_m = s.robot.wheel_radius_m;
  c.dt_s = s.dt();
  c.group_hold_s = s.control.group_hold_s;
  c.central_timeout_s = s.control.central_timeout_s;
  c.stop_decel_mps2 = s.control.stop_decel_mps2;
  return c;
}

bool tick_ok(const msg::PlantTick& t, std::size_t per_side) {
  for (double v : {t.t(), t.dt(), t.phidot_L(), t.phidot_R(), t.battery_V_L(), t.battery_V_R(), t.phidot_ref_L(),
                   t.phidot_ref_R()})
    if (!std::isfinite(v)) return false;
  return t.active_L().size() == per_side && t.active_R().size() == per_side && t.battery_V_L() >= 0 &&
         t.battery_V_R() >= 0;
}
}  // namespace

AgentNode::AgentNode(const comm::ProcessArgs& args, int side, int index, std::shared_ptr<spdlog::logger> log)
    : args_(args), side_(side), index_(index), log_(std::move(log)), core_(make_config(args.scenario)) {}

int AgentNode::run() {
  auto& stop = comm::stop_flag();
  // Listeners first: they must outlive the participant that calls them.
  comm::Signal signal;
  comm::Inbox<msg::PlantTick> ticks(signal);
  comm::MatchCounter reply_match(&signal);
  comm::Participant p(args_.name, args_.dds);
  auto* t_tick = p.topic<msg::PlantTickPubSubType>(comm::topic::kTick);
  auto* t_reply = p.topic<msg::AgentReplyPubSubType>(comm::topic::kAgentReply);
  auto* t_ready = p.topic<msg::NodeReadyPubSubType>(comm::topic::kReady);
  p.reader(t_tick, comm::Profile::kStream, &ticks);
  auto* w_reply = p.writer(t_reply, comm::Profile::kStream, &reply_match);
  auto* w_ready = p.writer(t_ready, comm::Profile::kLatched);

  const std::size_t per_side = static_cast<std::size_t>(args_.scenario.robot.per_side());
  bool announced = false;
  comm::PlantWatch plant;
  long long last_tick = -1;
  uint64_t rejected = 0;
  uint64_t seen = signal.count();
  log_->info("agent {} up (pid {})", args_.name, getpid());
  while (!stop.load()) {
    seen = signal.wait_until(seen, std::chrono::steady_clock::now() + std::chrono::milliseconds(200));
    if (!announced && ticks.matched() >= 1 && reply_match.matched() >= 1) {
      comm::announce_ready(w_ready, args_.name, msg::NODE_AGENT);
      announced = true;
      log_->info("matched the plant: ready");
    }
    if (plant.lost(ticks.drain_liveliness())) {
      log_->error("lost the plant (liveliness): exiting");
      return 3;
    }
    for (auto& [t, handle] : ticks.drain()) {
      if (!tick_ok(t, per_side) || static_cast<long long>(t.tick()) <= last_tick) {
        ++rejected;
        log_->warn("rejected malformed or stale tick {} ({} so far)", t.tick(), rejected);
        continue;
      }
      last_tick = static_cast<long long>(t.tick());
      if (t.run_state() != msg::RUN_RUNNING) {
        log_->info("run {} at tick {}: exiting", t.run_state() == msg::RUN_FINISHED ? "finished" : "aborted",
                   t.tick());
        return 0;
      }
      AgentInput in;
      in.tick = last_tick;
      in.phidot_rad_s = side_ == 0 ? t.phidot_L() : t.phidot_R();
      in.battery_V = side_ == 0 ? t.battery_V_L() : t.battery_V_R();
      in.phidot_ref_rad_s = side_ == 0 ? t.phidot_ref_L() : t.phidot_ref_R();
      in.central_stamp = t.central_stamp();
      in.group_stamp = side_ == 0 ? t.group_stamp_L() : t.group_stamp_R();
      in.assigned = (side_ == 0 ? t.active_L() : t.active_R())[index_] != 0;
      const AgentOutput out = core_.step(in);
      msg::AgentReply rep;
      rep.tick(t.tick());
      rep.side(static_cast<uint8_t>(side_));
      rep.index(static_cast<uint16_t>(index_));
      rep.pid(static_cast<uint32_t>(getpid()));
      rep.voltage_V(out.voltage_V);
      rep.current_A(out.current_A);
      rep.efficiency(out.efficiency);
      rep.state(static_cast<uint8_t>(out.state));
      rep.rejected(rejected);
      w_reply->write(&rep);
    }
  }
  log_->info("stop signal: exiting");
  return 0;
}

}  // namespace maptr::agent
