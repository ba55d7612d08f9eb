#include "plant/plant_node.hpp"

#include <algorithm>
#include <fstream>
#include <thread>

#include "idl/maptrPubSubTypes.h"
#include "plant/barrier.hpp"
#include "plant/fault_gate.hpp"
#include "plant/membership.hpp"
#include "plant/report.hpp"
#include "plant/run_files.hpp"
#include "plant/validation.hpp"
#include "sim/plant_core.hpp"

namespace maptr::plant {

namespace {

using Clock = std::chrono::steady_clock;
using Handle = eprosima::fastrtps::rtps::InstanceHandle_t;

WriterId writer_id(const Handle& h) {
  WriterId w;
  const eprosima::fastrtps::rtps::octet* p = h.value;
  std::copy(p, p + w.bytes.size(), w.bytes.begin());
  w.set = h.value.has_been_set();
  return w;
}

double wall_ms_now() {
  return std::chrono::duration<double, std::milli>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

float us(Clock::time_point a, Clock::time_point b) {
  return static_cast<float>(std::chrono::duration<double, std::micro>(b - a).count());
}

int count(const std::vector<uint8_t>& m) {
  int n = 0;
  for (auto b : m) n += b ? 1 : 0;
  return n;
}

/// What a MembershipEvent says, for the DDS-free membership (kOther: a value this build does not
/// know).
LauncherEvent launcher_event(msg::MemberEvent kind) {
  switch (kind) {
    case msg::MEMBER_DIED:
      return LauncherEvent::kDied;
    case msg::MEMBER_STARTED:
      return LauncherEvent::kStarted;
  }
  return LauncherEvent::kOther;
}

sim::PlantCoreConfig core_config(const config::Scenario& sc, const PlantNodeConfig& c) {
  sim::PlantCoreConfig pc;
  pc.robot = sc.robot;
  pc.dt_s = sc.dt();
  pc.trace_every = sc.trace_every;
  pc.initial_discharge_mAh = sc.initial_discharge_mAh;
  pc.stop_below_speed_pct = sc.stop_below_speed_pct;
  pc.speed_lost_hold_s = c.speed_lost_hold_s;
  pc.reached_band_pct = c.reached_band_pct;
  return pc;
}

std::vector<double> fault_times(const std::vector<config::FaultSpec>& faults) {
  std::vector<double> t;
  for (const auto& f : faults) t.push_back(f.at_s);
  return t;
}

/// What the members last commanded: each agent's applied voltage over the current tick, the
/// groups' assignments and central's references (carried in the next Tick).
struct Commands {
  std::vector<sim::AgentApplied> applied[2];
  std::vector<uint8_t> mask[2];
  long long group_stamp[2] = {-1, -1};
  long long central_stamp = -1;
  double ref[2] = {0.0, 0.0};  ///< rad/s, wheel references per side
  int relay[2] = {0, 0};       ///< the other side's active count, relayed to each side
};

/// Wall-clock instants of one lock-step tick.
struct TickTimes {
  Clock::time_point publish, start, first_reply, complete, done;
};

/// The plant's DDS endpoints and the protocol objects they feed.
class PlantLoop {
 public:
  PlantLoop(const comm::ProcessArgs& args, spdlog::logger& log, const PlantNodeConfig& c);

  bool discover();
  void open_records();
  /// True when the current tick is the last one to publish (duration reached or speed lost);
  /// stamps the membership records with its time and notes why the run ends.
  bool last_tick();
  void pass_gate();
  void publish(msg::RunState run_state);
  /// Waits until tick k is complete; false on the stop signal.
  bool collect();
  void integrate();
  void pace();
  int report(bool stopped);

 private:
  void wait_gate(long long k);
  void apply_launcher_events();
  void apply_liveliness();
  void take_replies(long long k, const SampleLimits& lim);
  void take_groups(long long k, const SampleLimits& lim);
  void take_centrals(long long k, const SampleLimits& lim);
  SampleLimits limits() const;
  void log_membership();
  void wait(std::chrono::milliseconds at_most);
  double now_s() const { return std::chrono::duration<double>(Clock::now() - origin_).count(); }

  const config::Scenario& sc_;
  const std::string run_dir_;
  spdlog::logger& log_;
  const PlantNodeConfig c_;
  const int per_side_;
  std::atomic<bool>& stop_;
  const Clock::time_point origin_ = Clock::now();

  comm::Signal signal_;
  comm::Inbox<msg::AgentReply> replies_{signal_};
  comm::Inbox<msg::GroupStatus> groups_{signal_};
  comm::Inbox<msg::CentralCommand> centrals_{signal_};
  comm::Inbox<msg::MembershipEvent> members_{signal_};
  comm::Inbox<msg::Control> controls_{signal_};
  comm::MatchCounter tick_match_{&signal_};
  comm::Participant p_;
  eprosima::fastdds::dds::DataWriter* w_tick_ = nullptr;
  eprosima::fastdds::dds::DataWriter* w_ready_ = nullptr;
  eprosima::fastdds::dds::DataWriter* w_gate_ = nullptr;
  uint64_t seen_ = 0;

  sim::PlantCore core_;
  std::unique_ptr<RunFiles> files_;
  Membership membership_;
  std::size_t logged_records_ = 0;
  FaultGate gate_;
  Barrier barrier_;
  Commands cmd_;
  msg::PlantTick sent_;  ///< the tick last published (resent unchanged to a restarted member)
  TickTimes times_;
  TickTiming timing_;
  Clock::time_point wall0_;
  std::string end_reason_ = "duration reached";
  uint64_t rejected_ = 0, missed_deadlines_ = 0, declared_dead_ = 0;
};

PlantLoop::PlantLoop(const comm::ProcessArgs& args, spdlog::logger& log, const PlantNodeConfig& c)
    : sc_(args.scenario),
      run_dir_(args.run_dir),
      log_(log),
      c_(c),
      per_side_(args.scenario.robot.per_side()),
      stop_(comm::stop_flag()),
      p_("plant", args.dds),
      core_(core_config(args.scenario, c)),
      membership_(per_side_, wall_ms_now),
      gate_(fault_times(args.scenario.faults), c.gate_timeout_s),
      barrier_(c.deadline_s(args.scenario.robot.agents), c.resend_s) {
  w_tick_ =
      p_.writer(p_.topic<msg::PlantTickPubSubType>(comm::topic::kTick), comm::Profile::kStream, &tick_match_);
  p_.reader(p_.topic<msg::AgentReplyPubSubType>(comm::topic::kAgentReply), comm::Profile::kStream, &replies_);
  p_.reader(p_.topic<msg::GroupStatusPubSubType>(comm::topic::kGroup), comm::Profile::kStream, &groups_);
  p_.reader(p_.topic<msg::CentralCommandPubSubType>(comm::topic::kCentral), comm::Profile::kStream,
            &centrals_);
  p_.reader(p_.topic<msg::MembershipEventPubSubType>(comm::topic::kMembership), comm::Profile::kLatched,
            &members_);
  p_.reader(p_.topic<msg::ControlPubSubType>(comm::topic::kControl), comm::Profile::kLatched, &controls_);
  w_ready_ = p_.writer(p_.topic<msg::NodeReadyPubSubType>(comm::topic::kReady), comm::Profile::kLatched);
  w_gate_ = p_.writer(p_.topic<msg::FaultGatePubSubType>(comm::topic::kGate), comm::Profile::kLatched);
  for (int s = 0; s < 2; ++s) {
    cmd_.applied[s].assign(per_side_, sim::AgentApplied{});
    cmd_.mask[s].assign(per_side_, 0);
  }
}

void PlantLoop::wait(std::chrono::milliseconds at_most) {
  seen_ = signal_.wait_until(seen_, Clock::now() + at_most);
}

// Every endpoint of the fleet matched, then tell the launcher; true once it says start.
bool PlantLoop::discover() {
  const int n_agents = sc_.robot.agents;
  const auto t_launch = Clock::now();
  seen_ = signal_.count();
  bool announced = false, started = false;
  while (!stop_.load() && !started) {
    wait(c_.discovery_poll);
    if (!announced && replies_.matched() >= n_agents && groups_.matched() >= 2 && centrals_.matched() >= 1 &&
        tick_match_.matched() >= n_agents + 4) {  // agents, 2 groups, central and the launcher
      comm::announce_ready(w_ready_, "plant", msg::NODE_PLANT);
      announced = true;
      log_.info("all {} agents, 2 groups and central matched after {:.2f} s", n_agents,
                std::chrono::duration<double>(Clock::now() - t_launch).count());
    }
    for (auto& [c, h] : controls_.drain())
      if (c.command() == msg::CONTROL_START) started = true;
  }
  return started;
}

void PlantLoop::open_records() {
  files_ = open_csv_run_files(run_dir_ + "/trace.csv", run_dir_ + "/assignments.csv");
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
    for (auto& [c, h] : controls_.drain())
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
  msg::PlantTick& t = sent_;
  t.tick(static_cast<uint64_t>(core_.tick()));
  t.t(core_.t());
  t.dt(sc_.dt());
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
  for (int s = 0; s < 2; ++s) {
    msg::SideTick& side = t.sides()[s];
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
  }
  t.run_state(run_state);
  w_tick_->write(&t);
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

// Launcher events: a death ends the wait for that process; a restarted process that is
// matched and ready is waited for from the next tick on (its old writer no longer counts).
void PlantLoop::apply_launcher_events() {
  for (auto& [e, h] : members_.drain()) {
    membership_.on_launcher(e.seq(), launcher_event(e.kind()), e.name());
  }
  log_membership();
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
  return l;
}

void PlantLoop::take_replies(long long k, const SampleLimits& lim) {
  for (auto& [r, h] : replies_.drain()) {
    const Verdict v = check(r, lim, k);
    if (v != Verdict::kAccepted) {
      ++rejected_;
      if (v == Verdict::kMalformed)
        log_.warn("rejected a malformed agent reply (side {}, index {}, V {})", r.side(), r.index(),
                  r.voltage_V());
      continue;
    }
    if (times_.first_reply == Clock::time_point{}) times_.first_reply = Clock::now();
    membership_.on_answer({Role::kAgent, static_cast<int>(r.side()), r.index()}, writer_id(h));
    cmd_.applied[r.side()][r.index()] = {true, drives(r), r.voltage_V(), r.current_A(), r.efficiency()};
  }
}

void PlantLoop::take_groups(long long k, const SampleLimits& lim) {
  for (auto& [g, h] : groups_.drain()) {
    if (check(g, lim, k) != Verdict::kAccepted) {
      ++rejected_;
      continue;
    }
    const int s = g.side();
    membership_.on_answer({Role::kGroup, s, 0}, writer_id(h));
    cmd_.mask[s] = g.active();
    for (int j = 0; j < per_side_; ++j)
      if (!membership_.at({Role::kAgent, s, j}).live)
        cmd_.mask[s][j] = 0;  // never trust a dead agent's assignment
    cmd_.group_stamp[s] = k;
  }
}

void PlantLoop::take_centrals(long long k, const SampleLimits& lim) {
  for (auto& [c, h] : centrals_.drain()) {
    if (check(c, lim, k) != Verdict::kAccepted) {
      ++rejected_;
      continue;
    }
    membership_.on_answer({Role::kCentral, 0, 0}, writer_id(h));
    for (int s = 0; s < 2; ++s) {
      cmd_.ref[s] = c.phidot_ref()[s];
      cmd_.relay[s] = c.relay_count_for()[s];
    }
    cmd_.central_stamp = k;
  }
}

bool PlantLoop::collect() {
  const long long k = core_.tick();
  membership_.begin_tick();
  for (auto& side : cmd_.applied)
    for (auto& a : side) a = sim::AgentApplied{};
  times_.start = Clock::now();
  times_.first_reply = Clock::time_point{};
  barrier_.start(now_s());
  const SampleLimits lim = limits();
  for (;;) {
    // Membership first, then the samples.
    apply_launcher_events();
    apply_liveliness();
    take_replies(k, lim);
    log_membership();
    take_groups(k, lim);
    take_centrals(k, lim);
    log_membership();
    if (Barrier::complete(membership_) || stop_.load()) break;
    // A restarted member may have matched the tick writer after tick k went out: send it again
    // (unchanged; followers that have it ignore the copy).
    if (barrier_.resend_due(membership_, now_s())) w_tick_->write(&sent_);
    if (barrier_.deadline_passed(now_s())) {
      declared_dead_ += membership_.on_deadline();
      log_membership();
      continue;
    }
    wait(c_.poll);
  }
  times_.complete = Clock::now();
  return !stop_.load();
}

void PlantLoop::integrate() {
  // Row k is written before the integration, so that a run whose integration fails keeps it.
  files_->write(core_.hold(cmd_.applied[0], cmd_.applied[1], cmd_.ref[0], cmd_.ref[1],
                           membership_.live_count(0), membership_.live_count(1)));
  core_.integrate();
  times_.done = Clock::now();
  const auto& t = times_;
  const float first = t.first_reply != Clock::time_point{} ? us(t.start, t.first_reply) : -1.0f;
  timing_.add(us(t.publish, t.start), first, us(t.start, t.complete), us(t.complete, t.done),
              us(t.publish, t.done));
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
  e.reached_reference = core_.reached_reference();
  e.speed_lost = core_.speed_lost();
  e.ref_speed_mps = 0.5 * (cmd_.ref[0] + cmd_.ref[1]) * sc_.robot.wheel_radius_m;
  e.speed_mps = core_.state()[model::kVx];
  ReportInputs in;
  in.status = run_status(e, c_.degraded_band_pct);
  in.end_reason = end_reason_;
  in.tick_hz = sc_.tick_hz;
  in.loop_wall_s = wall;
  in.live_agents[0] = e.live_agents[0];
  in.live_agents[1] = e.live_agents[1];
  in.rejected_samples = rejected_;
  in.missed_deadlines = missed_deadlines_;
  in.declared_dead_by_deadline = declared_dead_;
  in.tick_timing_us = timing_.json();
  std::ofstream(run_dir_ + "/plant.json") << plant_report(core_, in, membership_.records()).dump(2) << "\n";
  log_.info("run {} after {} ticks ({:.1f} s simulated, {:.2f} s wall)", in.status, core_.tick(), core_.t(),
            wall);
  // Give the last Tick time to reach every reader before the participant goes away.
  std::this_thread::sleep_for(c_.linger);
  return aborted(in.status) ? 1 : 0;
}

}  // namespace

PlantNode::PlantNode(const comm::ProcessArgs& args, std::shared_ptr<spdlog::logger> log,
                     PlantNodeConfig config)
    : args_(args), log_(std::move(log)), config_(config) {}

int PlantNode::run() {
  auto& stop = comm::stop_flag();
  PlantLoop loop(args_, *log_, config_);
  if (!loop.discover()) return 0;
  loop.open_records();
  bool stopped = false;
  while (!stop.load()) {
    const bool last = loop.last_tick();
    if (!last) loop.pass_gate();
    loop.publish(last ? msg::RUN_FINISHED : msg::RUN_RUNNING);
    if (last) break;
    if (!loop.collect()) {
      stopped = true;
      break;
    }
    loop.integrate();
    loop.pace();
  }
  return loop.report(stopped);
}

}  // namespace maptr::plant
