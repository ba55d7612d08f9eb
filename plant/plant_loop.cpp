#include "plant/plant_loop.hpp"

#include <algorithm>
#include <fstream>
#include <thread>
#include <tuple>

#include "comm/dds/fleet_guid.hpp"
#include "comm/lockstep/lockstep.hpp"
#include "comm/lockstep/tick_filter.hpp"
#include "config/core_configs.hpp"
#include "config/scenario.hpp"
#include "idl/rules.hpp"
#include "plant/discovery_wait.hpp"
#include "records/run_files.hpp"

namespace maptr::plant {

namespace {

double wall_ms_now() {
  return std::chrono::duration<double, std::milli>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

int count(const std::vector<uint8_t>& m) {
  int n = 0;
  for (auto b : m) n += b ? 1 : 0;
  return n;
}

std::vector<double> fault_times(const std::vector<config::FaultSpec>& faults) {
  std::vector<double> t;
  for (const auto& f : faults)
    if (!config::is_agent_fault_action(f.action)) t.push_back(f.at_s);  // applied at their tick, no gate
  return t;
}

/// What the members last commanded: each agent's applied voltage over the current tick, the

}  // namespace

PlantLoop::PlantLoop(const comm::ProcessArgs& args, spdlog::logger& log, const PlantNodeConfig& c)
    : sc_(args.scenario),
      run_dir_(args.run_dir),
      log_(log),
      c_(c),
      per_side_(args.scenario.robot.per_side()),
      stop_(comm::stop_flag()),
      p_("plant", args.dds),
      core_(config::plant_core_config(args.scenario, c.speed_lost_hold_s, c.reached_band_pct)),
      membership_(per_side_, wall_ms_now),
      gate_(fault_times(args.scenario.faults), c.gate_timeout_s),
      barrier_(c.deadline_s(args.scenario.robot.agents), c.resend_s) {
  tick_match_.only_fleet(args.dds.fleet_id);  // readers outside the fleet (a watcher) are no members
  // With the tick filter the writer evaluates each agent's filter and sends an agent only the
  // ticks it needs (comm/lockstep/tick_filter.hpp).
  if (sc_.uses_tick_filter()) comm::register_tick_filter(p_.raw(), &filter_gate_);
  w_tick_ = p_.writer(p_.topic<msg::PlantTickPubSubType>(comm::topic::kTick), comm::Profile::kStream, &tick_match_,
                      sc_.uses_tick_filter() ? comm::tick_filter_capacity(sc_.robot.agents) : 0);
  p_.reader(p_.topic<msg::AgentReplyPubSubType>(comm::topic::kAgentReply), comm::Profile::kStream, &replies_);
  p_.reader(p_.topic<msg::GroupStatusPubSubType>(comm::topic::kGroup), comm::Profile::kStream, &groups_);
  p_.reader(p_.topic<msg::CentralCommandPubSubType>(comm::topic::kCentral), comm::Profile::kStream,
            &centrals_);
  p_.reader(p_.topic<msg::MembershipEventPubSubType>(comm::topic::kMembership), comm::Profile::kLatched,
            &members_);
  p_.reader(p_.topic<msg::ControlPubSubType>(comm::topic::kControl), comm::Profile::kLatched, &controls_);
  w_ready_ = p_.writer(p_.topic<msg::NodeReadyPubSubType>(comm::topic::kReady), comm::Profile::kLatched);
  // Fast DDS opens another process's shared-memory port at the first write to it, and opening
  // one can wait out its health check (up to a third of a second): the members' readies (read
  // here) and the plant's hello (read by every member) open both ways before tick 0. The hello
  // is best effort: a reliable writer sends each reader a heartbeat as it matches, in Fast DDS's
  // discovery thread, which would then open the 512 ports there (at 512 agents the plant lost
  // hundreds of matches meanwhile); its one write opens them in this thread, after discovery.
  p_.reader(p_.topic<msg::NodeReadyPubSubType>(comm::topic::kReady), comm::Profile::kLatched, &readies_);
  hello_match_.only_fleet(args.dds.fleet_id);
  w_hello_ = p_.writer(p_.topic<msg::NodeReadyPubSubType>(comm::topic::kHello), comm::Profile::kStream,
                       &hello_match_);
  w_gate_ = p_.writer(p_.topic<msg::FaultGatePubSubType>(comm::topic::kGate), comm::Profile::kLatched);
  for (int s = 0; s < 2; ++s) {
    cmd_.applied[s].assign(per_side_, plant_core::AgentApplied{});
    agent_rejects_[s].assign(per_side_, 0);
    once_reply_[s].resize(static_cast<std::size_t>(per_side_));
    cmd_.mask[s].assign(per_side_, 0);
  }
}

void PlantLoop::wait(std::chrono::milliseconds at_most) {
  seen_ = signal_.wait_until(seen_, Clock::now() + at_most);
}

void PlantLoop::set_scheduling(std::string what) {
  scheduling_ = std::move(what);
  if (scheduling_.rfind("normal (", 0) == 0)
    log_.warn("lock-step thread: {}; the plant runs as any process (root or an rtprio limit allows it)",
              scheduling_);
  else
    log_.info("lock-step thread: {}", scheduling_);
}

void PlantLoop::open_records() {
  files_ = open_csv_run_files(records::trace_path(run_dir_), records::assignments_path(run_dir_));
  wall0_ = Clock::now();
}

bool PlantLoop::last_tick() {
  membership_.set_time(core_.t());
  if (core_.speed_lost() && end_reason_ == "duration reached")
    end_reason_ = end_reason(true, sc_.stop_below_speed_pct, c_.speed_lost_hold_s, core_.t());
  return core_.tick() >= sc_.ticks() || core_.speed_lost();
}

void PlantLoop::pass_gate() {
  if (!gate_.due(core_.t())) return;
  const auto t0 = Clock::now();
  wait_gate(core_.tick());
  wall0_ += Clock::now() - t0;  // a pause for fault injection is not a missed real-time deadline
}

// Holds tick k until the launcher has applied the faults due at t_k (see FaultGate).
void PlantLoop::wait_gate(long long k) {
  msg::FaultGate g;
  g.tick(static_cast<uint64_t>(k));
  g.t(core_.t());
  w_gate_->write(&g);
  gate_.hold(static_cast<uint64_t>(k));
  const double t0 = now_s();
  while (!stop_.load() && !gate_.released(membership_.launcher_seq())) {
    for (const auto& c : take_controls())
      if (c.command() == msg::CONTROL_GATE_OPEN) gate_.on_open(c.tick(), c.member_seq());
    apply_launcher_events();
    if (gate_.timed_out(now_s() - t0)) {
      log_.error("the launcher did not answer the fault gate of tick {} within {} s: going on", k,
                 gate_.timeout_s());
      break;
    }
    wait(c_.poll);
  }
}

void PlantLoop::publish(msg::RunState run_state) {
  times_.publish = Clock::now();
  if (last_publish_ != Clock::time_point{}) timing_.add_period(us(last_publish_, times_.publish));
  last_publish_ = times_.publish;
  msg::PlantTick& t = sent_;
  t.tick(static_cast<uint64_t>(core_.tick()));
  t.t(core_.t());
  const auto& x = core_.state();
  t.x(x[model::kX]);
  t.y(x[model::kY]);
  t.theta(x[model::kTheta]);
  t.v_x(x[model::kVx]);
  t.w(x[model::kW]);
  t.energy_J(x[model::kEnergyL] + x[model::kEnergyR]);
  t.distance_m(x[model::kDistance]);
  t.central_stamp(cmd_.central_stamp);
  const int charge[2] = {model::kChargeL, model::kChargeR};
  const bool new_tick = core_.tick() != published_tick_;
  for (int s = 0; s < 2; ++s) {
    msg::SideTick& side = t.sides()[s];
    // The values of tick k-1 for an agent that did not take it (the first tick: its own).
    if (new_tick) {
      side.phidot_prev(published_tick_ < 0 ? core_.phidot(s) : prev_phidot_[s]);
      side.phidot_ref_prev(published_tick_ < 0 ? cmd_.ref[s] : prev_ref_[s]);
      prev_phidot_[s] = core_.phidot(s);
      prev_ref_[s] = cmd_.ref[s];
    }
    side.phidot(core_.phidot(s));
    side.battery_V(core_.battery_V(s));
    side.V_active(core_.active_voltage(s));
    side.discharge_mAh(x[charge[s]]);
    side.phidot_ref(cmd_.ref[s]);
    side.active(cmd_.mask[s]);
    side.live(membership_.live_mask(s));
    side.group_stamp(cmd_.group_stamp[s]);
    side.n_active(static_cast<uint16_t>(count(cmd_.mask[s])));
    side.relay_count(static_cast<uint16_t>(cmd_.relay[s]));
    if (sc_.control.fault_detection && new_tick) put_measurements(side, s);
  }
  published_tick_ = core_.tick();
  t.paused(membership_.paused_mask());
  ledgers_.fill(t);
  t.run_state(run_state);
  set_wake();
  write_tick();
}

void PlantLoop::put_measurements(msg::SideTick& side, int s) {
  // What the drive measured over the tick just integrated (zeros at tick 0), filled in place.
  const auto& m = core_.measurements(s);
  const std::size_t n = m.size();
  side.drove().resize(n);
  side.drive_V().resize(n);
  side.measured_A().resize(n);
  side.reported().resize(n);
  side.reported_A().resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    side.drove()[j] = m[j].drove ? 1 : 0;
    side.drive_V()[j] = static_cast<float>(m[j].drive_V);
    side.measured_A()[j] = static_cast<float>(m[j].measured_A);
    side.reported()[j] = m[j].reported ? 1 : 0;
    side.reported_A()[j] = static_cast<float>(m[j].reported_A);
  }
}

void PlantLoop::set_wake() {
  const long long k = static_cast<long long>(sent_.tick());
  for (int s = 0; s < 2; ++s) {
    msg::SideTick& side = sent_.sides()[s];
    auto& wake = side.wake();  // filled in place: no allocation per tick
    wake.resize(static_cast<std::size_t>(per_side_));
    for (int j = 0; j < per_side_; ++j) {
      const auto i = static_cast<std::size_t>(j);
      wake[i] = side.active()[i] != 0 || comm::idle_answer_due(k, s, j, per_side_) ||
                membership_.at({Role::kAgent, s, j}).rejoining;
    }
  }
}

void PlantLoop::log_membership() {
  const auto& r = membership_.records();
  for (; logged_records_ < r.size(); ++logged_records_) {
    const auto& e = r[logged_records_];
    if (e.event == "rejoined")
      log_.info("{} answers again at t={:.2f} s: re-admitted", e.name, e.t_s);
    else
      log_.warn("{} {} at t={:.2f} s", e.name, e.event, e.t_s);
  }
}

bool PlantLoop::sent_by(const Handle& writer, int base_id) const {
  const uint32_t fleet = p_.options().fleet_id;
  return fleet == 0 || comm::written_by_id(fleet, sc_.robot.agents, writer, base_id);
}

uint64_t PlantLoop::own_rejects() const {
  return rejected_ + replies_.undecodable() + groups_.undecodable() + centrals_.undecodable() +
         members_.undecodable() + controls_.undecodable();
}

std::map<std::string, uint64_t> PlantLoop::rejects_by_process() const {
  std::map<std::string, uint64_t> m{{"plant", own_rejects()}, {"central", central_rejects_}};
  for (int s = 0; s < 2; ++s) {
    m[s == msg::SIDE_L ? "group-L" : "group-R"] = group_rejects_[s];
    for (int j = 0; j < per_side_; ++j) m[config::agent_name(s, j)] = agent_rejects_[s][static_cast<std::size_t>(j)];
  }
  return m;
}

// Launcher events: a death ends the wait for that process; a restarted process that is
// matched and ready is waited for from the next tick on (its old writer no longer counts).
void PlantLoop::apply_launcher_events() {
  const SampleLimits lim = limits();
  for (auto& [e, h] : members_.drain()) {
    const std::string name = e.name().substr(0, 64);
    if (!sent_by(h, comm::kLauncherParticipantId)) {
      if (reject("forged") <= kRejectsLogged)
        log_.warn("rejected a membership event for {} that the launcher did not send", name);
      continue;
    }
    // A malformed event, or one whose fields do not describe the process it names, is not
    // applied and does not move the launcher's sequence (a later gate waits for the real one).
    const bool ok = valid(e, lim);
    const bool applied =
        ok && membership_.on_launcher(e.seq(), launcher_event(e.kind()), name, e.participant_id());
    if (applied && e.kind() == msg::MEMBER_STARTED && e.node_kind() == msg::NODE_GROUP)
      ledgers_.on_started(e.side(), e.participant_id());
    if (!applied) {
      if (reject(ok ? "stale" : "malformed") <= kRejectsLogged)
        log_.warn(
            "rejected a {} membership event from the launcher's id: seq {} (last applied {}), name '{}', "
            "kind {}",
            ok ? "stale" : "malformed", e.seq(), membership_.launcher_seq(), name,
            static_cast<int>(e.kind()));
    }
  }
  log_membership();
}

std::vector<msg::Control> PlantLoop::take_controls() {
  // Drained at every tick, not only during discovery and at gates: what does not come from the
  // launcher, or is malformed, is counted whenever it arrives.
  std::vector<msg::Control> out;
  for (auto& [c, h] : controls_.drain()) {
    if (!sent_by(h, comm::kLauncherParticipantId)) {
      if (reject("forged") <= kRejectsLogged)
        log_.warn("rejected a control sample the launcher did not send");
      continue;
    }
    if (!msg::well_formed(c)) {
      if (reject("malformed") <= kRejectsLogged)
        log_.warn("rejected a malformed control sample from the launcher's id (command {}, seq {})",
                  static_cast<int>(c.command()), c.seq());
      continue;
    }
    out.push_back(c);
  }
  return out;
}

void PlantLoop::apply_liveliness() {
  for (const auto& ev : replies_.drain_liveliness())
    if (!ev.alive) membership_.on_liveliness_lost(Role::kAgent, writer_id(ev.writer));
  for (const auto& ev : groups_.drain_liveliness())
    if (!ev.alive) membership_.on_liveliness_lost(Role::kGroup, writer_id(ev.writer));
  for (const auto& ev : centrals_.drain_liveliness())
    if (!ev.alive) membership_.on_liveliness_lost(Role::kCentral, writer_id(ev.writer));
  log_membership();
}

SampleLimits PlantLoop::limits() const {
  SampleLimits l;
  l.per_side = per_side_;
  l.battery_V[0] = core_.battery_V(0);
  l.battery_V[1] = core_.battery_V(1);
  l.voltage_tolerance_V = c_.voltage_tolerance_V;
  l.ref_bound_radps = c_.central_ref_bound_radps;
  l.bidirectional = sc_.robot.driver.bidirectional;
  l.v_bound_mps = c_.central_v_bound_mps;
  l.w_bound_radps = c_.central_w_bound_radps;
  return l;
}

}  // namespace maptr::plant
