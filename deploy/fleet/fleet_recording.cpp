// The launcher's recorder (recorder/recorder.hpp): run.mcap's participant, started before the
// children; the start waits until it has matched every lock-step writer.
#include <algorithm>

#include "comm/dds/fleet_guid.hpp"
#include "comm/dds/fleet_ids.hpp"
#include "comm/posix/shm_files.hpp"
#include "deploy/fleet/fleet.hpp"
#include "records/compression.hpp"
#include "records/run_files.hpp"

namespace maptr::deploy::fleet {

void Fleet::start_recorder() {
  const auto scope = recorder::parse_scope(sc_.record);
  if (scope == recorder::Scope::kNone) return;
  // The recorder's participant takes the launcher's id in the second id window: no process of
  // the fleet ever has it (comm/dds/fleet_ids.hpp).
  comm::DdsOptions o = dds_;
  const int id = comm::fleet_stride(sc_.robot.agents) + comm::kLauncherParticipantId;
  o.participant_id = id <= comm::rtps_max_participant_id(o_.domain) ? id : -1;
  o.shm_port_queue = static_cast<uint32_t>(cfg_.recorder_port_queue(sc_.robot.agents));
  recorder_id_ = o.participant_id;
  recorder_ = std::make_unique<recorder::Recorder>(o, records::mcap_path(o_.run_dir), scope, sc_.robot.agents,
                                                   records::mcap_compression(sc_.record_compression));
}

void Fleet::await_recorder() {
  if (!recorder_) return;
  // Before the start, the recorder has matched every writer of the lock-step (the volatile
  // topics; the latched ones are resent to it). It joined before the children started, so each
  // writer has long discovered it too: a reader's match alone does not say that its writer sends
  // to it yet.
  const int agents = sc_.robot.agents;
  const std::map<std::string, int> writers = {{comm::topic::kTick, 1},    {comm::topic::kAgentReply, agents},
                                              {comm::topic::kGroup, 2},   {comm::topic::kCentral, 1},
                                              {comm::topic::kControl, 1}, {comm::topic::kMembership, 1}};
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(cfg_.discovery_timeout_s(agents)));
  // An agent can report ready (its writer matched the recorder's reader) while the recorder's
  // reader never matches its writer (seen once in a fleet of 512). Such agents are started again
  // after the rematch interval without progress, as the unready ones are during discovery.
  std::size_t matched = 0;
  auto progress = Clock::now();
  // Done when the recorder has matched every writer and every process is (again) ready.
  while (!recorder_->wait_matched(writers, std::min(deadline, Clock::now() + std::chrono::seconds(1))) ||
         ready_names_.size() < kids_.size()) {
    if (ready_names_.size() < kids_.size()) seen_ = signal_.wait_until(seen_, Clock::now() + cfg_.discovery_poll);
    take_ready();
    reap(false);
    if (interrupted().load()) return;
    if (Clock::now() > deadline) {
      log_.warn("recorder: not every writer matched before the start ({}; not ready: {}); run.mcap misses their "
                "samples until they match",
                recorder_->missing(), not_ready());
      return;
    }
    const std::size_t now_matched = recorder_->matched_writers(comm::topic::kAgentReply).size();
    if (now_matched != matched) {
      matched = now_matched;
      progress = Clock::now();
    }
    if (since(progress) > cfg_.rematch_s(agents, secure()) && rematch_unrecorded()) progress = Clock::now();
  }
}

bool Fleet::rematch_unrecorded() {
  // written_by() names a writer by the fleet id in its GUID prefix, or on a secure domain by the
  // certificate that prefix was derived from (comm/dds/fleet_guid.hpp).
  const auto seen = recorder_->matched_writers(comm::topic::kAgentReply);
  std::vector<Child*> unseen;
  for (auto& c : kids_) {
    if (c.kind != ChildKind::kAgent || c.external || !c.running) continue;
    const bool recorded = std::any_of(seen.begin(), seen.end(), [&](const auto& h) {
      return comm::written_by(dds_.fleet_id, sc_.robot.agents, h, c.name);
    });
    if (!recorded) unseen.push_back(&c);
  }
  for (Child* c : unseen) {
    start_again(*c);
    ready_names_.erase(c->name);
    rec_.rematched.push_back(c->name);
    log_.warn("run.mcap's recorder did not match {}'s writer within {:.0f} s; started it again (pid {})", c->name,
              cfg_.rematch_s(sc_.robot.agents, secure()), c->pid);
  }
  if (unseen.empty()) return false;
  // The restarted agents report ready again before the start.
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(cfg_.rematch_s(sc_.robot.agents, secure())));
  while (ready_names_.size() < kids_.size() && Clock::now() < until && !interrupted().load()) {
    seen_ = signal_.wait_until(seen_, Clock::now() + cfg_.discovery_poll);
    take_ready();
    reap(false);
  }
  return true;
}

void Fleet::stop_recorder() {
  if (!recorder_) return;
  recorder_->stop();
  std::string counts;
  for (const auto& [topic, n] : recorder_->counts()) counts += " " + topic + " " + std::to_string(n);
  rec_.recorded = recorder_->counts();
  rec_.recorded_rejected = recorder_->rejected();
  std::string dropped;
  for (const auto& [kind, n] : rec_.recorded_rejected) dropped += " " + kind + " " + std::to_string(n);
  log_.info("recorded run.mcap:{}{}", counts, dropped.empty() ? "" : "; marked as dropped by the fleet:" + dropped);
}

}  // namespace maptr::deploy::fleet
