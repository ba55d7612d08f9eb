#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <thread>

#include "comm/dds/fleet_guid.hpp"
#include "comm/dds/fleet_ids.hpp"
#include "comm/lockstep/lockstep.hpp"
#include "config/scenario.hpp"
#include "control/diagnosis.hpp"
#include "model/kinematics.hpp"
#include "plant/plant_loop.hpp"
#include "records/run_files.hpp"

namespace maptr::plant {

bool PlantLoop::admit(Verdict v, bool own, unsigned long long tick, long long k, const char* what, int side,
                      int index) {
  if (own && repeated(v, tick, k)) return false;
  if (own && late(v, tick, k)) {
    ++kinds_["late"];
    if (++late_ <= kRejectsLogged)
      log_.info("a late {} (side {}, index {}) for tick {} at tick {}: not used", what, side, index, tick, k);
    return false;
  }
  if (own && v == Verdict::kAccepted) return true;
  // Not its sender's: forged (even when malformed too); its sender's: malformed, or an answer
  // to a tick after k (none has been sent): other_tick.
  const char* kind = !own ? "forged" : v == Verdict::kMalformed ? "malformed" : "other_tick";
  if (reject(kind) <= kRejectsLogged)
    log_.warn("rejected a{} {} (side {}, index {}) for tick {} at tick {}{}",
              v == Verdict::kMalformed ? " malformed" : "", what, side, index, tick, k,
              own ? "" : ", from a participant other than its sender's");
  return false;
}

const char* const* PlantLoop::diagnosis_names() {
  static const auto names = [] {
    std::array<const char*, control::kDiagnosisCount> a{};
    for (int i = 0; i < control::kDiagnosisCount; ++i) a[i] = control::diagnosis_name(static_cast<control::Diagnosis>(i));
    return a;
  }();
  return names.data();
}

void PlantLoop::log_diagnoses(int side, const std::vector<uint8_t>& flags) {
  if (flags.size() != static_cast<std::size_t>(per_side_)) return;
  for (int j = 0; j < per_side_; ++j) {
    const bool was = core_.faults().disconnected(side, j), now = flags[static_cast<std::size_t>(j)] != 0;
    if (was == now) continue;
    if (now)
      log_.warn("{} isolated by its group at t={:.2f} s ({}): its motor is disconnected", config::agent_name(side, j),
                core_.t(), control::diagnosis_name(static_cast<control::Diagnosis>(flags[static_cast<std::size_t>(j)])));
    else
      log_.info("{} let back by its group at t={:.2f} s", config::agent_name(side, j), core_.t());
  }
}

bool PlantLoop::once(Once o, const char* what, int side, int index, long long k) {
  if (o == Once::kFirst) return true;
  if (o == Once::kConflict && reject("conflicting") <= kRejectsLogged)
    log_.warn(
        "rejected a second, different {} (side {}, index {}) for tick {} from the same writer: the first is "
        "used",
        what, side, index, k);
  return false;
}

bool PlantLoop::one_writer(const MemberId& id, const Handle& h, long long k) {
  // A controller has one writer between two starts: the one of its first answer after the
  // launcher announced its start. A stranded copy (its host cut off while the launcher started
  // it elsewhere) that is heard again after the heal is not it.
  const auto participant = comm::fleet_participant(p_.options().fleet_id, h);  // none on a secure domain
  if (membership_.takes(id, writer_id(h), participant ? *participant : -1)) return true;
  if (reject("stale_copy") <= kRejectsLogged)
    log_.warn("rejected {}'s sample for tick {} from a writer other than its current one (an earlier copy)",
              member_name(id), k);
  return false;
}

uint64_t PlantLoop::reject(const char* kind) {
  ++kinds_[kind];
  return ++rejected_;
}

void PlantLoop::take_replies(long long k, const SampleLimits& lim) {
  auto replies = replies_.drain();
  consumed_ += replies.size();
  for (auto& [r, h] : replies) {
    const bool own = sent_by(h, comm::agent_participant_id(r.side(), r.index(), sc_.robot.agents));
    if (!admit(check(r, lim, k), own, r.tick(), k, "agent reply", r.side(), r.index())) continue;
    if (!once(once_reply_[r.side()][r.index()].see(r, k), "agent reply", r.side(), r.index(),
              k))
      continue;
    if (times_.first_reply == Clock::time_point{}) times_.first_reply = Clock::now();
    times_.note.last = TickNote::kAgent;
    ++taken_[0];
    membership_.on_answer({Role::kAgent, static_cast<int>(r.side()), r.index()}, writer_id(h));
    cmd_.applied[r.side()][r.index()] = {true, drives(r), r.voltage_V(), r.current_A(), r.efficiency()};
    agent_rejects_[r.side()][r.index()] = r.rejected();
  }
}

void PlantLoop::take_groups(long long k, const SampleLimits& lim) {
  auto statuses = groups_.drain();
  consumed_ += statuses.size();
  for (auto& [g, h] : statuses) {
    const bool own = sent_by(h, comm::group_participant_id(g.side()));
    if (!admit(check(g, lim, k), own, g.tick(), k, "group status", g.side(), 0)) continue;
    const int s = g.side();
    if (!one_writer({Role::kGroup, s, 0}, h, k)) continue;
    if (!once(once_group_[s].see(g, k), "group status", s, 0, k)) continue;
    ++taken_[1];
    times_.note.last = TickNote::kGroup;
    times_.note.level2_solving = times_.note.level2_solving || g.level2_solving();
    membership_.on_answer({Role::kGroup, s, 0}, writer_id(h));
    cmd_.mask[s] = g.active();
    for (int j = 0; j < per_side_; ++j)
      if (!membership_.at({Role::kAgent, s, j}).live)
        cmd_.mask[s][j] = 0;  // never trust a dead agent's assignment
    cmd_.group_stamp[s] = k;
    group_rejects_[s] = g.rejected();
    log_diagnoses(s, g.faulty());
    core_.on_group_flags(s, g.faulty(), diagnosis_names(), control::kDiagnosisCount);
    const int before = wear_.regressions(s);
    wear_.on_status(s, g.ledger().wear_m(), core_.t());
    ledgers_.on_status(s, g);
    if (wear_.regressions(s) > before)
      log_.error("group-{}'s wear ledger went backwards at t={:.2f} s", s == 0 ? "L" : "R", core_.t());
  }
}

void PlantLoop::take_centrals(long long k, const SampleLimits& lim) {
  auto commands = centrals_.drain();
  consumed_ += commands.size();
  for (auto& [c, h] : commands) {
    const bool own = sent_by(h, comm::kCentralParticipantId);
    if (!admit(check(c, lim, k), own, c.tick(), k, "central command", 0, 0)) continue;
    if (!one_writer({Role::kCentral, 0, 0}, h, k)) continue;
    if (!once(once_central_.see(c, k), "central command", 0, 0, k)) continue;
    ++taken_[2];
    times_.note.last = TickNote::kCentral;
    membership_.on_answer({Role::kCentral, 0, 0}, writer_id(h));
    for (int s = 0; s < 2; ++s) {
      cmd_.ref[s] = c.phidot_ref()[s];
      cmd_.relay[s] = c.relay_count_for()[s];
    }
    cmd_.central_stamp = k;
    central_rejects_ = c.rejected();
  }
}

bool PlantLoop::collect() {
  const long long k = core_.tick();
  // An idle agent (not assigned in tick k) answers only when its slot is due (comm/lockstep/lockstep.hpp).
  membership_.begin_tick([&](int side, int index) {
    return sent_.sides()[side].active()[index] == 0 && !comm::idle_answer_due(k, side, index, per_side_);
  });
  for (auto& side : cmd_.applied)
    for (auto& a : side) a = plant_core::AgentApplied{};
  times_.start = Clock::now();
  times_.first_reply = Clock::time_point{};
  times_.note = TickNote{};
  times_.note.tick = k;
  barrier_.start(now_s());
  const SampleLimits lim = limits();
  for (;;) {
    const uint64_t seen = signal_.count();
    // Membership first, then the samples.
    apply_launcher_events();
    apply_liveliness();
    take_controls();  // between gates a control sample has nothing to do: checked and counted only
    take_replies(k, lim);
    log_membership();
    take_groups(k, lim);
    take_centrals(k, lim);
    log_membership();
    if (Barrier::complete(membership_) || stop_.load()) break;
    // A restarted member may have matched the tick writer after tick k went out: send it again
    // (followers that have answered it answer again with the same sample). A member resumed
    // between two ticks finds itself no longer marked paused in the copy.
    if (barrier_.resend_due(membership_, now_s())) {
      sent_.paused(membership_.paused_mask());
      set_wake();
      write_tick();
    }
    if (barrier_.repair_due(consumed_, now_s())) {
      ++repairs_;
      write_tick();
    }
    if (barrier_.deadline_passed(now_s())) {
      declared_dead_ += membership_.on_deadline();
      log_membership();
      continue;
    }
    wait_for_answers(seen, c_.poll);
  }
  signal_.wake_at(0);
  times_.complete = Clock::now();
  const double w = c_.barrier_average_weight;
  barrier_average_s_ = (1.0 - w) * barrier_average_s_ + w * us(times_.start, times_.complete) * 1e-6;
  barrier_.set_repair(barrier_average_s_, c_.repair_factor, c_.repair_min_s);
  return !stop_.load();
}

void PlantLoop::wait_for_answers(uint64_t seen, std::chrono::milliseconds at_most) {
  const uint64_t want = consumed_ + static_cast<uint64_t>(Barrier::late_count(membership_));
  signal_.wake_at(want);
  if (signal_.arrivals() >= want) return;  // already here: take them
  seen_ = signal_.wait_until(seen, Clock::now() + at_most);
}

void PlantLoop::integrate() {
  for (int s = 0; s < 2; ++s)
    for (int j = 0; j < per_side_; ++j)
      cmd_.applied[s][static_cast<std::size_t>(j)].disconnected = core_.faults().disconnected(s, j);
  // Row k is written before the integration, so that a run whose integration fails keeps it.
  const plant_core::TickRecord rec = core_.hold(cmd_.applied[0], cmd_.applied[1], cmd_.ref[0], cmd_.ref[1],
                                                membership_.live_count(0), membership_.live_count(1));
  files_->write(rec);
  times_.note.traced = rec.row.has_value();
  core_.integrate();
  times_.done = Clock::now();
  const auto& t = times_;
  const float first = t.first_reply != Clock::time_point{} ? us(t.start, t.first_reply) : -1.0f;
  timing_.add(us(t.publish, t.start), first, us(t.start, t.complete), us(t.complete, t.done),
              us(t.publish, t.done), t.note);
}

void PlantLoop::pace() {
  if (!sc_.realtime) return;
  const auto due =
      wall0_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(core_.t()));
  if (Clock::now() > due)
    ++missed_deadlines_;
  else
    std::this_thread::sleep_until(due);
}

int PlantLoop::report(bool stopped) {
  const double wall = std::chrono::duration<double>(Clock::now() - wall0_).count();
  RunEnd e;
  e.stopped = stopped;
  for (int s = 0; s < 2; ++s) e.live_agents[s] = membership_.live_count(s);
  for (const auto& id : membership_.all())
    if (id.role != Role::kAgent && (!membership_.at(id).live || membership_.at(id).paused))
      e.silent_controllers.push_back(member_name(id));
  e.reached_reference = core_.reached_reference();
  e.speed_lost = core_.speed_lost();
  e.ref_speed_mps = model::speed_from_rates({cmd_.ref[0], cmd_.ref[1]}, sc_.robot.wheel_radius_m);
  e.speed_mps = core_.state()[model::kVx];
  e.cross_track_max_m = core_.tracking().cross_track_max();
  e.cross_track_max_t_s = core_.tracking().cross_track_max_t();
  e.path_tolerance_m = sc_.control.path_tolerance_m;
  if (sc_.control.fault_detection)
    e.fault_problems =
        fault_problems(core_.faults(), 2 * std::max(1LL, std::llround(sc_.control.fault_persistence_s / sc_.dt())) + 2);
  ReportInputs in;
  in.status = run_status(e, c_.degraded_band_pct);
  in.end_reason = end_reason_;
  in.tick_hz = sc_.tick_hz;
  in.loop_wall_s = wall;
  in.live_agents[0] = e.live_agents[0];
  in.live_agents[1] = e.live_agents[1];
  in.rejected_samples = own_rejects();
  in.rejected_by_process = rejects_by_process();
  in.rejected_by_kind = kinds_;
  in.rejected_by_kind["undecodable"] = own_rejects() - rejected_;
  in.late_samples = late_;
  in.missed_deadlines = missed_deadlines_;
  in.loop_scheduling = scheduling_;
  in.tick_repairs = repairs_;
  if (filter_gate_.timeouts() > 0)
    log_.warn("{} tick writes went ahead of a filter change whose end was not signalled", filter_gate_.timeouts());
  in.answers_taken = {{comm::topic::kAgentReply, taken_[0]}, {comm::topic::kGroup, taken_[1]},
                      {comm::topic::kCentral, taken_[2]}};
  in.declared_dead_by_deadline = declared_dead_;
  in.tick_timing_us = timing_.json();
  in.group_wear = wear_.json();
  records::write_plant_results(run_dir_, plant_results(core_, in, membership_.records()));
  try {
    ledgers_.save(run_dir_);
  } catch (const std::exception& e) {
    log_.error("{}", e.what());
  }
  log_.info("run {} after {} ticks ({:.1f} s simulated, {:.2f} s wall)", in.status, core_.tick(), core_.t(),
            wall);
  // Give the last Tick time to reach every reader before the participant goes away.
  std::this_thread::sleep_for(c_.linger);
  return aborted(in.status) ? 1 : 0;
}

}  // namespace maptr::plant
