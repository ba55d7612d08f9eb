#include "group/group_node.hpp"

#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>

#include "comm/lockstep/follower.hpp"
#include "config/core_configs.hpp"
#include "config/scenario.hpp"
#include "group/group_wire.hpp"
#include "records/level2_log.hpp"

namespace maptr::group {

namespace {
std::chrono::milliseconds level2_pause{0};
}  // namespace

void set_level2_pause(std::chrono::milliseconds pause) { level2_pause = pause; }

GroupNode::GroupNode(const comm::ProcessArgs& args, int side, std::shared_ptr<spdlog::logger> log)
    : args_(args),
      side_(side),
      log_(std::move(log)),
      worker_(args.scenario.control.oracle, level2_pause),
      core_(side, config::group_config(args.scenario), std::nullopt, &worker_) {}

void GroupNode::resume_from(const msg::PlantTick& t) {
  if (const auto ledger = kept_ledger(t, side_, args_.dds.participant_id)) {
    core_.resume(*ledger);
    log_->info("resumed the wear ledger the plant kept: {} decisions, {} reallocations so far",
               core_.ledger().decisions, core_.ledger().reallocations);
  } else if (t.tick() > 0) {
    log_->error("started at tick {} without a kept wear ledger: the side's wear starts from zero", t.tick());
  }
}

void GroupNode::report(const control::GroupInput& in, const control::GroupDecision& d) {
  if (d.level2_ran && (d.level2.status == control::kL2Infeasible) != infeasible_) {
    infeasible_ = !infeasible_;
    if (infeasible_)
      log_->warn(
          "Level 2 infeasible at t={:.2f} s: {} live agents cannot hold the reference; all of them run", in.t,
          d.n_live);
    else
      log_->info("Level 2 feasible again at t={:.2f} s", in.t);
  }
  for (const auto& ch : d.diagnosed) {
    const std::string name = config::agent_name(side_, ch.index);
    if (ch.flag == control::Diagnosis::kNone)
      log_->info("{} let back after its probation at t={:.2f} s", name, in.t);
    else
      log_->warn("{} isolated at t={:.2f} s: it looks {} (its measurements disagree with the motor model)",
                 name, in.t, control::diagnosis_name(ch.flag));
  }
}

int GroupNode::run() {
  comm::TickFollower follower(args_, msg::NODE_GROUP, log_);
  follower.answer_writer<msg::GroupStatusPubSubType>(comm::topic::kGroup);
  if (level2_pause.count() > 0)
    log_->info("every Level-2 solve is followed by a {} ms pause (a slow solver, set_level2_pause)",
               level2_pause.count());
  // Every Level-2 decision, for the solve-time and oracle figures (appended: a restarted
  // controller continues the file).
  std::optional<records::Level2LogWriter> l2;
  try {
    l2.emplace(records::level2_log_path(args_.run_dir, side_));
  } catch (const records::RecordError& e) {
    log_->warn("{}: the group runs on without its Level-2 log", e.what());
  }
  bool first = true;
  const int code = follower.run([&](const msg::PlantTick& t) {
    if (first) resume_from(t);  // a restarted group's first tick carries the ledger it goes on from
    first = false;
    const control::GroupInput in = group_input(t, side_);
    const control::GroupDecision d = core_.step(in);
    report(in, d);
    if (d.level2_ran && l2) l2->write(d.level2);
    msg::GroupStatus st = group_status(t, side_, in, d, core_.ledger());
    st.rejected(follower.rejected());
    st.level2_solving(worker_.solving());  // timing only: what the plant's slowest ticks overlapped
    follower.answer(st);
  });
  log_->info(
      "Level 2: {} decisions solved on the worker thread, {} of them waited for at the tick they were due",
      worker_.finished(), worker_.waited());
  log_->info("wear ledger at the end: {} decisions, {} reallocations", core_.ledger().decisions,
             core_.ledger().reallocations);
  return code;
}

}  // namespace maptr::group
