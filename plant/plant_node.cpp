#include "plant/plant_node.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "idl/maptrPubSubTypes.h"
#include "plant/plant_core.hpp"

namespace maptr::plant {

namespace {

using Clock = std::chrono::steady_clock;
using Handle = eprosima::fastrtps::rtps::InstanceHandle_t;

/// Wall time the plant waits for the launcher at a fault gate before going on, s.
constexpr double kGateTimeoutS = 120.0;
/// Wall time after which tick k is sent again to a restarted member that has not answered, s.
constexpr double kResendS = 0.2;

struct Member {
  bool live = true;        ///< waited for at each tick
  bool answered = false;   ///< answered the current tick
  Handle writer{};         ///< DDS writer, learnt from its first sample
  bool writer_known = false;
  bool rejoining = false;  ///< restarted (launcher): expected from the next tick, not yet heard
};

/// Simulated times at which the plant holds its tick for the launcher's fault injection: the
/// first tick at or after each scheduled fault (FaultGate / CONTROL_GATE_OPEN).
std::vector<double> gate_times(const std::vector<config::FaultSpec>& faults) {
  std::vector<double> t;
  for (const auto& f : faults) t.push_back(f.at_s);
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

int count(const std::vector<uint8_t>& m) {
  int n = 0;
  for (auto b : m) n += b ? 1 : 0;
  return n;
}

}  // namespace

PlantNode::PlantNode(const comm::ProcessArgs& args, std::shared_ptr<spdlog::logger> log)
    : args_(args), log_(std::move(log)) {}

int PlantNode::run() {
  const config::Scenario& sc = args_.scenario;
  const int per_side = sc.robot.per_side();
  const int n_agents = sc.robot.agents;
  auto& stop = comm::stop_flag();

  comm::Signal signal;
  comm::Inbox<msg::AgentReply> replies(signal);
  comm::Inbox<msg::GroupStatus> groups(signal);
  comm::Inbox<msg::CentralCommand> centrals(signal);
  comm::Inbox<msg::MembershipEvent> members(signal);
  comm::Inbox<msg::Control> controls(signal);
  comm::MatchCounter tick_match(&signal);
  comm::Participant p("plant", args_.dds);
  auto* w_tick = p.writer(p.topic<msg::PlantTickPubSubType>(comm::topic::kTick), comm::Profile::kStream, &tick_match);
  p.reader(p.topic<msg::AgentReplyPubSubType>(comm::topic::kAgentReply), comm::Profile::kStream, &replies);
  p.reader(p.topic<msg::GroupStatusPubSubType>(comm::topic::kGroup), comm::Profile::kStream, &groups);
  p.reader(p.topic<msg::CentralCommandPubSubType>(comm::topic::kCentral), comm::Profile::kStream, &centrals);
  p.reader(p.topic<msg::MembershipEventPubSubType>(comm::topic::kMembership), comm::Profile::kLatched, &members);
  p.reader(p.topic<msg::ControlPubSubType>(comm::topic::kControl), comm::Profile::kLatched, &controls);
  auto* w_ready = p.writer(p.topic<msg::NodeReadyPubSubType>(comm::topic::kReady), comm::Profile::kLatched);
  auto* w_gate = p.writer(p.topic<msg::FaultGatePubSubType>(comm::topic::kGate), comm::Profile::kLatched);

  // 1. Discovery: every endpoint of the fleet matched, then tell the launcher.
  const auto t_launch = Clock::now();
  uint64_t seen = signal.count();
  bool announced = false, started = false;
  while (!stop.load() && !started) {
    seen = signal.wait_until(seen, Clock::now() + std::chrono::milliseconds(200));
    if (!announced && replies.matched() >= n_agents && groups.matched() >= 2 && centrals.matched() >= 1 &&
        tick_match.matched() >= n_agents + 4) {  // agents, 2 groups, central and the launcher
      comm::announce_ready(w_ready, "plant", msg::NODE_PLANT);
      announced = true;
      log_->info("all {} agents, 2 groups and central matched after {:.2f} s", n_agents,
                 std::chrono::duration<double>(Clock::now() - t_launch).count());
    }
    for (auto& [c, h] : controls.drain())
      if (c.command() == msg::CONTROL_START) started = true;
  }
  if (!started) return 0;

  // 2. Lock-step.
  PlantCore core(sc, args_.run_dir + "/trace.csv", args_.run_dir + "/assignments.csv");
  std::string end_reason = "duration reached";
  std::vector<Member> agent[2] = {std::vector<Member>(per_side), std::vector<Member>(per_side)};
  Member group[2], central;
  std::vector<AgentApplied> applied[2] = {std::vector<AgentApplied>(per_side), std::vector<AgentApplied>(per_side)};
  std::vector<uint8_t> mask[2] = {std::vector<uint8_t>(per_side, 0), std::vector<uint8_t>(per_side, 0)};
  long long group_stamp[2] = {-1, -1}, central_stamp = -1;
  double ref_L = 0.0, ref_R = 0.0;
  int relay_L = 0, relay_R = 0;
  uint64_t rejected = 0, missed_deadlines = 0, declared_dead = 0;
  nlohmann::json events = nlohmann::json::array();
  // One record per membership change: who, what, simulated time and wall clock (ms since the
  // epoch, comparable with the launcher's fault times).
  auto record = [&](const std::string& name, const std::string& what) {
    const double wall_ms =
        std::chrono::duration<double, std::milli>(std::chrono::system_clock::now().time_since_epoch()).count();
    events.push_back({{"name", name}, {"event", what}, {"t_s", core.t()}, {"wall_ms", wall_ms}});
  };
  // Deadline: the last resort only; it grows with the fleet (slow is not dead).
  const double deadline_s = 5.0 + 0.05 * n_agents;
  const long long total = sc.ticks();
  auto wall0 = Clock::now();
  std::string status = "ok";
  // Wall-clock cost of each lock-step tick, µs (diagnostics for `maptr bench tick`).
  struct {
    std::vector<float> publish, first_reply, barrier, integrate, tick;
  } timing;

  auto live_mask = [&](int s) {
    std::vector<uint8_t> m(per_side);
    for (int j = 0; j < per_side; ++j) m[j] = agent[s][j].live ? 1 : 0;
    return m;
  };
  msg::PlantTick sent;  // the tick last published (resent unchanged to a restarted member)
  auto publish = [&](uint8_t run_state) {
    msg::PlantTick& t = sent;
    t.tick(static_cast<uint64_t>(core.tick()));
    t.t(core.t());
    t.dt(sc.dt());
    const auto& x = core.state();
    t.x(x[model::kX]);
    t.y(x[model::kY]);
    t.theta(x[model::kTheta]);
    t.v_x(x[model::kVx]);
    t.w(x[model::kW]);
    t.phidot_L(core.phidot(0));
    t.phidot_R(core.phidot(1));
    t.battery_V_L(core.battery_V(0));
    t.battery_V_R(core.battery_V(1));
    t.V_active_L(core.active_voltage(0));
    t.V_active_R(core.active_voltage(1));
    t.discharge_mAh_L(x[model::kChargeL]);
    t.discharge_mAh_R(x[model::kChargeR]);
    t.energy_J(x[model::kEnergyL] + x[model::kEnergyR]);
    t.distance_m(x[model::kDistance]);
    t.phidot_ref_L(ref_L);
    t.phidot_ref_R(ref_R);
    t.central_stamp(central_stamp);
    t.active_L(mask[0]);
    t.active_R(mask[1]);
    t.group_stamp_L(group_stamp[0]);
    t.group_stamp_R(group_stamp[1]);
    t.live_L(live_mask(0));
    t.live_R(live_mask(1));
    t.n_active_L(static_cast<uint16_t>(count(mask[0])));
    t.n_active_R(static_cast<uint16_t>(count(mask[1])));
    t.relay_count_L(static_cast<uint16_t>(relay_L));
    t.relay_count_R(static_cast<uint16_t>(relay_R));
    t.run_state(run_state);
    w_tick->write(&t);
  };
  auto mark_dead_by_name = [&](const std::string& name, const char* why) {
    int s = 0, j = 0;
    bool was_live = false;
    if (config::parse_agent_name(name, s, j) && j < per_side) {
      was_live = agent[s][j].live;
      agent[s][j].live = false;
    } else if (name == "group-L" || name == "group-R") {
      was_live = group[name == "group-L" ? 0 : 1].live;
      group[name == "group-L" ? 0 : 1].live = false;
    } else if (name == "central") {
      was_live = central.live;
      central.live = false;
    }
    if (!was_live) return;
    record(name, why);
    log_->warn("{} {} at t={:.2f} s", name, why, core.t());
  };
  auto mark_alive = [&](Member& m, const std::string& name) {
    if (!m.live || m.rejoining) {
      record(name, "rejoined");
      log_->info("{} answers again at t={:.2f} s: re-admitted", name, core.t());
    }
    m.live = true;
    m.rejoining = false;
  };
  // A member by its process name, or nullptr.
  auto member_by_name = [&](const std::string& name) -> Member* {
    int s = 0, j = 0;
    if (config::parse_agent_name(name, s, j) && j < per_side) return &agent[s][j];
    if (name == "group-L" || name == "group-R") return &group[name == "group-L" ? 0 : 1];
    if (name == "central") return &central;
    return nullptr;
  };
  // Launcher events: a death ends the wait for that process; a restarted process that is
  // matched and ready is waited for from the next tick on (its old writer no longer counts).
  uint64_t member_seen = 0;
  auto apply_members = [&] {
    for (auto& [e, h] : members.drain()) {
      member_seen = std::max<uint64_t>(member_seen, e.seq());
      if (e.kind() == msg::MEMBER_DIED) mark_dead_by_name(e.name(), "died (launcher)");
      if (e.kind() == msg::MEMBER_STARTED)
        if (Member* m = member_by_name(e.name())) {
          m->live = true;
          m->rejoining = true;
          m->writer_known = false;
        }
    }
  };
  // Holds tick k until the launcher has applied the faults due at t_k (see FaultGate).
  const std::vector<double> gates = gate_times(sc.faults);
  std::size_t next_gate = 0;
  auto wait_gate = [&](long long k) {
    msg::FaultGate g;
    g.tick(static_cast<uint64_t>(k));
    g.t(core.t());
    w_gate->write(&g);
    const auto t0 = Clock::now();
    bool open = false;
    uint64_t need = 0;
    while (!stop.load() && !(open && member_seen >= need)) {
      for (auto& [c, h] : controls.drain())
        if (c.command() == msg::CONTROL_GATE_OPEN && c.tick() == static_cast<uint64_t>(k)) {
          open = true;
          need = c.member_seq();
        }
      apply_members();
      if (Clock::now() - t0 > std::chrono::duration<double>(kGateTimeoutS)) {
        log_->error("the launcher did not answer the fault gate of tick {} within {} s: going on", k, kGateTimeoutS);
        break;
      }
      seen = signal.wait_until(seen, Clock::now() + std::chrono::milliseconds(50));
    }
    return Clock::now() - t0;
  };

  while (!stop.load()) {
    const long long k = core.tick();
    if (core.speed_lost() && end_reason == "duration reached")
      end_reason = "the speed stayed more than " + std::to_string(sc.stop_below_speed_pct) +
                   "% below its reference for 5 s at t=" + std::to_string(core.t()) + " s";
    const bool last = k >= total || core.speed_lost();
    if (!last && next_gate < gates.size() && core.t() >= gates[next_gate]) {
      while (next_gate < gates.size() && core.t() >= gates[next_gate]) ++next_gate;
      wall0 += wait_gate(k);  // a pause for fault injection is not a missed real-time deadline
    }
    const auto t_pub = Clock::now();
    publish(last ? msg::RUN_FINISHED : msg::RUN_RUNNING);
    if (last) break;
    for (int s = 0; s < 2; ++s) {
      for (auto& m : agent[s]) m.answered = false;
      for (auto& a : applied[s]) a = AgentApplied{};
      group[s].answered = false;
    }
    central.answered = false;
    const auto tick_start = Clock::now();
    auto last_send = tick_start;
    Clock::time_point t_first{};
    bool got_central = false, got_group[2] = {false, false};
    for (;;) {
      // Membership first, then the samples.
      apply_members();
      for (const auto& ev : replies.drain_liveliness())
        if (!ev.alive)
          for (int s = 0; s < 2; ++s)
            for (int j = 0; j < per_side; ++j)
              if (agent[s][j].writer_known && agent[s][j].writer == ev.writer && agent[s][j].live)
                mark_dead_by_name(config::agent_name(s, j), "lost (DDS liveliness)");
      for (const auto& ev : groups.drain_liveliness())
        if (!ev.alive)
          for (int s = 0; s < 2; ++s)
            if (group[s].writer_known && group[s].writer == ev.writer)
              mark_dead_by_name(s == 0 ? "group-L" : "group-R", "lost (DDS liveliness)");
      for (const auto& ev : centrals.drain_liveliness())
        if (!ev.alive && central.writer_known && central.writer == ev.writer)
          mark_dead_by_name("central", "lost (DDS liveliness)");

      for (auto& [r, h] : replies.drain()) {
        const bool ok = r.side() <= 1 && r.index() < per_side && std::isfinite(r.voltage_V()) &&
                        std::isfinite(r.current_A()) && std::isfinite(r.efficiency()) && r.voltage_V() >= 0.0 &&
                        r.voltage_V() <= core.battery_V(r.side()) + 1e-9 && r.state() <= msg::AGENT_STOPPING;
        if (!ok || static_cast<long long>(r.tick()) != k) {
          ++rejected;
          if (!ok) log_->warn("rejected a malformed agent reply (side {}, index {}, V {})", r.side(), r.index(), r.voltage_V());
          continue;
        }
        if (t_first == Clock::time_point{}) t_first = Clock::now();
        Member& m = agent[r.side()][r.index()];
        mark_alive(m, config::agent_name(r.side(), r.index()));
        m.answered = true;
        m.writer = h;
        m.writer_known = true;
        AgentApplied& a = applied[r.side()][r.index()];
        a.replied = true;
        a.drives = r.state() == msg::AGENT_ACTIVE || r.state() == msg::AGENT_HOLDING || r.state() == msg::AGENT_STOPPING;
        a.voltage_V = r.voltage_V();
        a.current_A = r.current_A();
        a.efficiency = r.efficiency();
      }
      for (auto& [g, h] : groups.drain()) {
        const bool ok = g.side() <= 1 && g.active().size() == static_cast<std::size_t>(per_side);
        if (!ok || static_cast<long long>(g.tick()) != k) {
          ++rejected;
          continue;
        }
        const int s = g.side();
        mark_alive(group[s], s == 0 ? "group-L" : "group-R");
        group[s].answered = true;
        group[s].writer = h;
        group[s].writer_known = true;
        got_group[s] = true;
        mask[s] = g.active();
        for (int j = 0; j < per_side; ++j)
          if (!agent[s][j].live) mask[s][j] = 0;  // never trust an assignment of a dead agent
        group_stamp[s] = k;
      }
      for (auto& [c, h] : centrals.drain()) {
        const bool ok = std::isfinite(c.phidot_ref_L()) && std::isfinite(c.phidot_ref_R()) &&
                        std::fabs(c.phidot_ref_L()) < 1e4 && std::fabs(c.phidot_ref_R()) < 1e4;
        if (!ok || static_cast<long long>(c.tick()) != k) {
          ++rejected;
          continue;
        }
        mark_alive(central, "central");
        central.answered = true;
        central.writer = h;
        central.writer_known = true;
        got_central = true;
        ref_L = c.phidot_ref_L();
        ref_R = c.phidot_ref_R();
        relay_L = c.relay_count_for_L();
        relay_R = c.relay_count_for_R();
        central_stamp = k;
      }
      bool complete = (!central.live || central.answered) && (!group[0].live || group[0].answered) &&
                      (!group[1].live || group[1].answered);
      for (int s = 0; s < 2 && complete; ++s)
        for (const auto& m : agent[s])
          if (m.live && !m.answered) complete = false;
      if (complete || stop.load()) break;
      // A restarted member may have matched the tick writer after tick k went out: send it again
      // (unchanged; followers that have it ignore the copy).
      bool rejoin_waits = false;
      for (int s = 0; s < 2; ++s) {
        for (const auto& m : agent[s]) rejoin_waits |= m.rejoining && !m.answered;
        rejoin_waits |= group[s].rejoining && !group[s].answered;
      }
      rejoin_waits |= central.rejoining && !central.answered;
      if (rejoin_waits && Clock::now() - last_send > std::chrono::duration<double>(kResendS)) {
        w_tick->write(&sent);
        last_send = Clock::now();
      }
      if (Clock::now() - tick_start > std::chrono::duration<double>(deadline_s)) {
        for (int s = 0; s < 2; ++s)
          for (int j = 0; j < per_side; ++j)
            if (agent[s][j].live && !agent[s][j].answered) {
              mark_dead_by_name(config::agent_name(s, j), "missed the tick deadline");
              ++declared_dead;
            }
        for (int s = 0; s < 2; ++s)
          if (group[s].live && !group[s].answered)
            mark_dead_by_name(s == 0 ? "group-L" : "group-R", "missed the tick deadline");
        if (central.live && !central.answered) mark_dead_by_name("central", "missed the tick deadline");
        continue;
      }
      seen = signal.wait_until(seen, Clock::now() + std::chrono::milliseconds(50));
    }
    if (stop.load()) {
      status = "aborted: stop signal";
      break;
    }
    (void)got_central;
    (void)got_group;
    int live_n[2] = {count(live_mask(0)), count(live_mask(1))};
    const auto t_complete = Clock::now();
    core.advance(applied[0], applied[1], ref_L, ref_R, live_n[0], live_n[1]);
    const auto t_done = Clock::now();
    auto us = [](Clock::time_point a, Clock::time_point b) {
      return static_cast<float>(std::chrono::duration<double, std::micro>(b - a).count());
    };
    timing.publish.push_back(us(t_pub, tick_start));
    if (t_first != Clock::time_point{}) timing.first_reply.push_back(us(tick_start, t_first));
    timing.barrier.push_back(us(tick_start, t_complete));
    timing.integrate.push_back(us(t_complete, t_done));
    timing.tick.push_back(us(t_pub, t_done));
    if (sc.realtime) {
      const auto due = wall0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(core.t()));
      if (Clock::now() > due)
        ++missed_deadlines;
      else
        std::this_thread::sleep_until(due);
    }
  }
  const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
  // A side with no live agent, or a speed that could not be held, is a degraded run.
  const int live_end[2] = {count(live_mask(0)), count(live_mask(1))};
  if (status == "ok") {
    if (live_end[0] == 0 || live_end[1] == 0)
      status = std::string("degraded: side ") + (live_end[0] == 0 ? "L" : "R") + " has no live agent; the robot stopped";
    else if (core.reached_reference() && !core.speed_lost()) {  // a run too short to reach its speed is not degraded
      const double ref_v = 0.5 * (ref_L + ref_R) * sc.robot.wheel_radius_m;
      const double err = ref_v > 0.0 ? 100.0 * std::fabs(core.state()[model::kVx] - ref_v) / ref_v : 0.0;
      if (err > 5.0)
        status = "degraded: the robot ended " + std::to_string(err) + "% off its reference speed";
    }
  }
  const auto& x = core.state();
  nlohmann::json j;
  j["status"] = status;
  j["sim_time_s"] = core.t();
  j["ticks"] = core.tick();
  j["tick_hz"] = sc.tick_hz;
  j["loop_wall_s"] = wall;
  j["distance_m"] = x[model::kDistance];
  j["energy_J"] = x[model::kEnergyL] + x[model::kEnergyR];
  j["energy_side_J"] = {{"L", x[model::kEnergyL]}, {"R", x[model::kEnergyR]}};
  j["mean_active_agents"] = core.mean_active_agents();
  j["active_agents"] = {{"L", core.last_active(0)}, {"R", core.last_active(1)}};
  j["live_agents"] = {{"L", live_end[0]}, {"R", live_end[1]}};
  j["battery_discharge_mAh"] = {{"L", core.drawn_mAh(0)}, {"R", core.drawn_mAh(1)}};
  j["battery_state_mAh"] = {{"L", x[model::kChargeL]}, {"R", x[model::kChargeR]}};
  j["agent_active_s"] = {{"L", core.active_time(0)}, {"R", core.active_time(1)}};
  j["end_reason"] = end_reason;
  j["battery_V"] = {{"L", core.battery_V(0)}, {"R", core.battery_V(1)}};
  j["pose"] = {{"x_m", x[model::kX]}, {"y_m", x[model::kY]}, {"theta_rad", x[model::kTheta]}};
  j["final_speed_mps"] = x[model::kVx];
  j["max_speed_error_pct"] = core.max_speed_error_pct();
  j["rms_speed_error_pct"] = core.rms_speed_error_pct();
  j["rejected_samples"] = rejected;
  j["missed_deadlines"] = missed_deadlines;
  auto stats = [](std::vector<float> v) {
    if (v.empty()) return nlohmann::json::object();
    std::sort(v.begin(), v.end());
    auto q = [&](double p) { return v[static_cast<std::size_t>(p * (v.size() - 1))]; };
    return nlohmann::json{{"median", q(0.5)}, {"p90", q(0.9)}, {"p99", q(0.99)}, {"n", v.size()}};
  };
  j["tick_timing_us"] = {{"publish", stats(timing.publish)},
                         {"first_reply", stats(timing.first_reply)},
                         {"barrier", stats(timing.barrier)},
                         {"integrate", stats(timing.integrate)},
                         {"tick", stats(timing.tick)}};
  j["declared_dead_by_deadline"] = declared_dead;
  j["membership_events"] = events;
  std::ofstream(args_.run_dir + "/plant.json") << j.dump(2) << "\n";
  log_->info("run {} after {} ticks ({:.1f} s simulated, {:.2f} s wall)", status, core.tick(), core.t(), wall);
  // Give the last Tick time to reach every reader before the participant goes away.
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  return status.rfind("aborted", 0) == 0 ? 1 : 0;
}

}  // namespace maptr::plant
