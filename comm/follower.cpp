#include "comm/follower.hpp"

#include <cstdlib>

#include "comm/fleet_guid.hpp"

#include <unistd.h>

#include <cmath>

namespace maptr::comm {

bool tick_valid(const msg::PlantTick& t, std::size_t per_side) {
  for (double v : {t.t(), t.dt(), t.x(), t.y(), t.theta(), t.v_x(), t.w(), t.energy_J(), t.distance_m()})
    if (!std::isfinite(v)) return false;
  for (const msg::SideTick& s : t.sides()) {
    for (double v : {s.phidot(), s.battery_V(), s.discharge_mAh(), s.phidot_ref(), s.V_active()})
      if (!std::isfinite(v)) return false;
    if (s.active().size() != per_side || s.live().size() != per_side || s.battery_V() < 0 || s.V_active() < 0)
      return false;
  }
  return true;
}

TickFollower::TickFollower(const ProcessArgs& args, msg::NodeKind node_kind,
                           std::shared_ptr<spdlog::logger> log)
    : args_(args), kind_(node_kind), log_(std::move(log)) {
  participant_ = std::make_unique<Participant>(args_.name, args_.dds);
  auto& p = *participant_;
  p.reader(p.topic<msg::PlantTickPubSubType>(topic::kTick), Profile::kStream, &ticks_);
  ready_ = p.writer(p.topic<msg::NodeReadyPubSubType>(topic::kReady), Profile::kLatched);
}

bool TickFollower::from_plant(const eprosima::fastrtps::rtps::InstanceHandle_t& writer) {
  const int agents = args_.scenario.robot.agents;
  if (args_.dds.fleet_id != 0) return written_by_id(args_.dds.fleet_id, agents, writer, kPlantParticipantId);
  // No fleet id (a process started by hand without one): the first writer heard is the plant.
  if (!plant_writer_) plant_writer_ = writer;
  return *plant_writer_ == writer;
}

int TickFollower::run(const std::function<void(const msg::PlantTick&)>& on_tick) {
  auto& stop = stop_flag();
  const std::size_t per_side = static_cast<std::size_t>(args_.scenario.robot.per_side());
  // On a fleet of several hosts the launcher sets MAPTR_PLANT_LOSS_S: a process cut off by a
  // network partition waits that long for the plant to come back instead of two leases.
  const char* loss = std::getenv("MAPTR_PLANT_LOSS_S");
  PlantWatch plant(loss ? std::atof(loss) : 2.0 * args_.dds.lease_s);
  bool announced = false;
  long long last_tick = -1;
  uint64_t seen = signal_.count();
  log_->info("{} up (pid {})", args_.name, getpid());
  while (!stop.load()) {
    seen = signal_.wait_until(seen, std::chrono::steady_clock::now() + std::chrono::milliseconds(200));
    if (!announced && ticks_.matched() >= 1 && answer_match_.matched() >= 1) {
      announce_ready(ready_, args_.name, kind_);
      announced = true;
      log_->info("matched the plant: ready");
    }
    plant.update(ticks_.drain_liveliness());
    if (plant.lost()) {
      log_->error("lost the plant (liveliness): exiting");
      return 3;
    }
    for (auto& [t, handle] : ticks_.drain()) {
      if (!from_plant(handle)) {
        ++rejected_;
        log_->warn("rejected a tick {} from a writer that is not the plant ({} so far)", t.tick(), rejected_);
        continue;
      }
      // The plant sends a tick again for a restarted member: a copy of the last one is no news.
      if (tick_valid(t, per_side) && static_cast<long long>(t.tick()) == last_tick) continue;
      if (!tick_valid(t, per_side) || static_cast<long long>(t.tick()) <= last_tick) {
        ++rejected_;
        log_->warn("rejected a malformed or stale tick {} ({} so far)", t.tick(), rejected_);
        continue;
      }
      last_tick = static_cast<long long>(t.tick());
      plant.heard();
      if (t.run_state() != msg::RUN_RUNNING) {
        log_->info("run {} at tick {}: exiting", t.run_state() == msg::RUN_FINISHED ? "finished" : "aborted",
                   t.tick());
        return 0;
      }
      on_tick(t);
    }
  }
  log_->info("stop signal: exiting");
  return 0;
}

}  // namespace maptr::comm
