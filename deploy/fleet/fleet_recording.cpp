// The fleet's side of run.mcap's recorder (fleet_recorder.hpp): started before the children;
// the start waits until it has matched every lock-step writer, starting again the agents it
// does not match.
#include "deploy/fleet/fleet.hpp"

namespace maptr::deploy::fleet {

void Fleet::start_recorder() { recorder_ = std::make_unique<FleetRecorder>(sc_, dds_, cfg_, o_.run_dir); }

void Fleet::await_recorder() {
  if (!recorder_->on()) return;
  // Before the start, the recorder has matched every writer of the lock-step (the volatile
  // topics; the latched ones are resent to it). It joined before the children started, so each
  // writer has long discovered it too: a reader's match alone does not say that its writer sends
  // to it yet.
  const int agents = sc_.robot.agents;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(cfg_.discovery_timeout_s(agents)));
  // An agent can report ready (its writer matched the recorder's reader) while the recorder's
  // reader never matches its writer (seen once in a fleet of 512). Such agents are started again
  // after the rematch interval without progress, as the unready ones are during discovery.
  std::size_t matched = 0;
  auto progress = Clock::now();
  // Done when the recorder has matched every writer and every process is (again) ready.
  while (!recorder_->matched_lockstep(std::min(deadline, Clock::now() + std::chrono::seconds(1))) ||
         ready_names_.size() < kids_.size()) {
    if (ready_names_.size() < kids_.size()) domain_->wait_until(Clock::now() + cfg_.discovery_poll);
    take_ready();
    reap(false);
    if (interrupted().load()) return;
    if (Clock::now() > deadline) {
      log_.warn("recorder: not every writer matched before the start ({}; not ready: {}); run.mcap misses their "
                "samples until they match",
                recorder_->missing(), not_ready());
      return;
    }
    if (const std::size_t now_matched = recorder_->agents_matched(); now_matched != matched) {
      matched = now_matched;
      progress = Clock::now();
    }
    if (since(progress) > cfg_.rematch_s(agents, secure()) && rematch_unrecorded()) progress = Clock::now();
  }
}

bool Fleet::rematch_unrecorded() {
  const std::vector<Child*> unseen = recorder_->unrecorded(kids_);
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
    domain_->wait_until(Clock::now() + cfg_.discovery_poll);
    take_ready();
    reap(false);
  }
  return true;
}

}  // namespace maptr::deploy::fleet
