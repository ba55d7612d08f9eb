#include "group/group_node.hpp"

#include <unistd.h>

#include <cmath>

#include "idl/maptrPubSubTypes.h"

namespace maptr::group {

namespace {
bool tick_ok(const msg::PlantTick& t, std::size_t per_side) {
  for (double v : {t.t(), t.v_x(), t.w(), t.phidot_L(), t.phidot_R(), t.battery_V_L(), t.battery_V_R(),
                   t.phidot_ref_L(), t.phidot_ref_R()})
    if (!std::isfinite(v)) return false;
  return t.active_L().size() == per_side && t.active_R().size() == per_side && t.live_L().size() == per_side &&
         t.live_R().size() == per_side;
}
}  // namespace

GroupNode::GroupNode(const comm::ProcessArgs& args, int side, std::shared_ptr<spdlog::logger> log)
    : args_(args),
      side_(side),
      log_(std::move(log)),
      core_(side, args.scenario, args.run_dir + "/ledger-" + (side == 0 ? "L" : "R") + ".json") {}

int GroupNode::run() {
  auto& stop = comm::stop_flag();
  comm::Signal signal;
  comm::Inbox<msg::PlantTick> ticks(signal);
  comm::MatchCounter status_match(&signal);
  comm::Participant p(args_.name, args_.dds);
  auto* t_tick = p.topic<msg::PlantTickPubSubType>(comm::topic::kTick);
  auto* t_group = p.topic<msg::GroupStatusPubSubType>(comm::topic::kGroup);
  auto* t_ready = p.topic<msg::NodeReadyPubSubType>(comm::topic::kReady);
  p.reader(t_tick, comm::Profile::kStream, &ticks);
  auto* w_group = p.writer(t_group, comm::Profile::kStream, &status_match);
  auto* w_ready = p.writer(t_ready, comm::Profile::kLatched);

  if (core_.resumed())
    log_->info("resumed the wear ledger: {} decisions, {} reallocations so far", core_.ledger().decisions,
               core_.ledger().reallocations);
  const std::size_t per_side = static_cast<std::size_t>(args_.scenario.robot.per_side());
  bool announced = false;
  comm::PlantWatch plant;
  long long last_tick = -1;
  uint64_t rejected = 0;
  uint64_t seen = signal.count();
  int code = 0;
  while (!stop.load()) {
    seen = signal.wait_until(seen, std::chrono::steady_clock::now() + std::chrono::milliseconds(200));
    if (!announced && ticks.matched() >= 1 && status_match.matched() >= 1) {
      comm::announce_ready(w_ready, args_.name, msg::NODE_GROUP);
      announced = true;
      log_->info("matched the plant: ready");
    }
    if (plant.lost(ticks.drain_liveliness())) {
      log_->error("lost the plant (liveliness): exiting");
      code = 3;
      break;
    }
    bool finished = false;
    for (auto& [t, handle] : ticks.drain()) {
      if (!tick_ok(t, per_side) || static_cast<long long>(t.tick()) <= last_tick) {
        ++rejected;
        log_->warn("rejected malformed or stale tick {} ({} so far)", t.tick(), rejected);
        continue;
      }
      last_tick = static_cast<long long>(t.tick());
      if (t.run_state() != msg::RUN_RUNNING) {
        finished = true;
        break;
      }
      GroupInput in;
      in.tick = last_tick;
      in.t = t.t();
      in.v_x = t.v_x();
      in.w = t.w();
      in.phidot_side = side_ == 0 ? t.phidot_L() : t.phidot_R();
      in.phidot_ref_L = t.phidot_ref_L();
      in.phidot_ref_R = t.phidot_ref_R();
      in.battery_V = side_ == 0 ? t.battery_V_L() : t.battery_V_R();
      in.live = side_ == 0 ? t.live_L() : t.live_R();
      in.active = side_ == 0 ? t.active_L() : t.active_R();
      in.n_other = side_ == 0 ? t.relay_count_L() : t.relay_count_R();
      const GroupDecision d = core_.step(in);
      msg::GroupStatus st;
      st.tick(t.tick());
      st.side(static_cast<uint8_t>(side_));
      st.active(d.active);
      st.live(in.live);
      st.wear_m(core_.ledger().wear_m);
      st.n_active(static_cast<uint16_t>(d.n_active));
      st.n_live(static_cast<uint16_t>(d.n_live));
      st.n_other(static_cast<uint16_t>(in.n_other));
      st.level2_status(d.level2_status);
      st.level2_relaxed(d.level2_relaxed);
      st.oracle_n_active(static_cast<int16_t>(d.oracle_n_active));
      st.solve_time_ms(d.solve_time_ms);
      st.decisions(d.decisions);
      st.reallocations(d.reallocations);
      st.rejected(rejected);
      w_group->write(&st);
    }
    if (finished) {
      log_->info("run ended at tick {}: exiting", last_tick);
      break;
    }
  }
  core_.save();
  log_->info("ledger saved: {} decisions, {} reallocations", core_.ledger().decisions, core_.ledger().reallocations);
  return code;
}

}  // namespace maptr::group
