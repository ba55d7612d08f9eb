#include "comm/lockstep/follower.hpp"

#include <unistd.h>

#include <cstdlib>
#include <thread>

#include "comm/dds/fleet_guid.hpp"
#include "comm/lockstep/lockstep.hpp"
#include "comm/lockstep/tick_filter.hpp"
#include "comm/posix/environment.hpp"
#include "config/scenario.hpp"

namespace maptr::comm {

int paused_slot(const std::string& name, int per_side) {
  int side = 0, index = 0;
  if (config::parse_agent_name(name, side, index)) return index < per_side ? side * per_side + index : -1;
  if (name == "group-L") return 2 * per_side;
  if (name == "group-R") return 2 * per_side + 1;
  if (name == "central") return 2 * per_side + 2;
  return -1;
}

bool paused_in(const msg::PlantTick& t, int slot) {
  return slot >= 0 && static_cast<std::size_t>(slot) < t.paused().size() && t.paused()[slot] != 0;
}

TickFollower::TickFollower(const ProcessArgs& args, msg::NodeKind node_kind,
                           std::shared_ptr<spdlog::logger> log)
    : args_(args), kind_(node_kind), log_(std::move(log)) {
  answer_match_.only_fleet(args_.dds.fleet_id);  // a watcher of the answers is not the plant
  participant_ = std::make_unique<Participant>(args_.name, args_.dds);
  auto& p = *participant_;
  auto* tick = p.topic<msg::PlantTickPubSubType>(topic::kTick);
  // An agent takes the ticks it needs only (comm/lockstep/tick_filter.hpp), unless the run says otherwise.
  int side = 0, index = 0;
  if (node_kind == msg::NODE_AGENT && args_.scenario.uses_tick_filter() &&
      config::parse_agent_name(args_.name, side, index))
    p.reader(agent_tick_topic(p.raw(), tick, side, index), Profile::kStream, &ticks_);
  else
    p.reader(tick, Profile::kStream, &ticks_);
  ready_ = p.writer(p.topic<msg::NodeReadyPubSubType>(topic::kReady), Profile::kLatched);
  // Read only so that the plant's hello opens this process's port before tick 0 (topic::kHello).
  p.reader(p.topic<msg::NodeReadyPubSubType>(topic::kHello), Profile::kStream, &hello_);
}

bool TickFollower::from_plant(const eprosima::fastrtps::rtps::InstanceHandle_t& writer) {
  const int agents = args_.scenario.robot.agents;
  if (args_.dds.fleet_id != 0) return written_by_id(args_.dds.fleet_id, agents, writer, kPlantParticipantId);
  // No fleet id (a process started by hand without one): the first writer heard is the plant.
  if (!plant_writer_) plant_writer_ = writer;
  return *plant_writer_ == writer;
}

void TickFollower::on_sample(const msg::PlantTick& t,
                             const eprosima::fastrtps::rtps::InstanceHandle_t& writer,
                             const std::function<void(const msg::PlantTick&)>& on_tick) {
  if (finished_.load()) return;
  if (!from_plant(writer)) {
    const uint64_t n = ++rejected_;
    log_->warn("rejected a tick {} from a writer that is not the plant ({} so far)", t.tick(), n);
    return;
  }
  const std::size_t per_side = static_cast<std::size_t>(args_.scenario.robot.per_side());
  const TickVerdict v = classify_tick(t, per_side, last_tick_);
  // The plant sends a tick again for a restarted member or when answers are missing: answer
  // the copy with the same answer (the plant takes an answer once).
  if (v == TickVerdict::kRepeat) {
    if (resend_ && answered_tick_ == last_tick_) resend_();
    return;
  }
  if (v == TickVerdict::kRejected) {
    const uint64_t n = ++rejected_;
    log_->warn("rejected a malformed or stale tick {} ({} so far)", t.tick(), n);
    return;
  }
  heard_.store(true);
  // A tick that marks this process paused is skipped and not taken as the last one: the plant
  // may send the same tick again without the mark (a resume between two ticks).
  if (t.run_state() == msg::RUN_RUNNING && paused_in(t, slot_)) {
    ++skipped_paused_;
    return;
  }
  last_tick_ = static_cast<long long>(t.tick());
  if (t.run_state() != msg::RUN_RUNNING) {
    log_->info("run {} at tick {}: exiting", t.run_state() == msg::RUN_FINISHED ? "finished" : "aborted",
               t.tick());
    finished_.store(true);
    signal_.notify();
    return;
  }
  ++followed_;
  on_tick(t);
}

int TickFollower::run(const std::function<void(const msg::PlantTick&)>& on_tick) {
  auto& stop = stop_flag();
  // On a fleet of several hosts the launcher sets MAPTR_PLANT_LOSS_S: a process cut off by a
  // network partition waits that long for the plant to come back instead of two leases.
  const char* loss = std::getenv(kEnvPlantLoss);
  PlantWatch plant(loss ? std::atof(loss) : 2.0 * args_.dds.lease_s);
  bool announced = false;
  uint64_t seen = signal_.count();
  slot_ = paused_slot(args_.name, args_.scenario.robot.per_side());
  log_->info("{} up (pid {})", args_.name, getpid());
  // Each tick is answered on the DDS receive thread; this loop watches readiness, the plant's
  // liveliness and the end of the run.
  ticks_.set_handler([&](const msg::PlantTick& t, const eprosima::fastrtps::rtps::InstanceHandle_t& w) {
    on_sample(t, w, on_tick);
  });
  // The plant's reader of the answers, and the recorder's when run.mcap records them
  // (comm/lockstep/lockstep.hpp).
  const int recorded = recorder_readers(args_.scenario.record, false);
  const int answer_readers = 1 + recorded;
  int code = 0;
  while (!stop.load() && !finished_.load()) {
    seen = signal_.wait_until(seen, std::chrono::steady_clock::now() + std::chrono::milliseconds(200));
    if (!announced && ticks_.matched() >= 1 && answer_match_.matched() >= answer_readers) {
      announce_ready(ready_, args_.name, kind_);
      announced = true;
      log_->info("matched the plant: ready");
    }
    if (heard_.exchange(false)) plant.heard();
    plant.update(ticks_.drain_liveliness());
    if (plant.lost() && !finished_.load()) {
      log_->error("lost the plant (liveliness): exiting");
      code = 3;
      break;
    }
  }
  ticks_.set_handler(nullptr);  // no answer leaves once run() has returned
  log_->info("followed {} ticks ({} skipped while paused, {} rejected)", followed_.load(),
             skipped_paused_.load(), rejected());
  if (stop.load() && !finished_.load()) log_->info("stop signal: exiting");
  // The recorder takes every answer on one thread, which a loaded machine may keep waiting for a
  // core; an answer still queued for it when this participant ends is lost to run.mcap (seen as
  // the last 1-6 ticks' answers missing with both cores saturated). So the participant stays a
  // moment after the run's end.
  if (finished_.load() && recorded > 0) {
    const auto until = std::chrono::steady_clock::now() + kRecorderDrain;
    while (!stop.load() && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return code;
}

}  // namespace maptr::comm
