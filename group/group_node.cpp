#include "group/group_node.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "comm/follower.hpp"
#include "comm/side.hpp"
#include "config/scenario.hpp"
#include "records/ledger_file.hpp"
#include "records/level2_log.hpp"

namespace maptr::group {

namespace {
/// The group core's Level-2 outcome (control::Level2Status) as the message carries it.
msg::Level2Status to_msg_level2(uint8_t s) {
  switch (s) {
    case control::kL2Ok:
      return msg::L2_OK;
    case control::kL2Infeasible:
      return msg::L2_INFEASIBLE;
    case control::kL2Failed:
      return msg::L2_SOLVER_FAILED;
    default:
      return msg::L2_NONE;
  }
}

control::GroupConfig make_config(const config::Scenario& s) {
  control::GroupConfig c;
  c.robot = s.robot;
  c.mode = s.mode == "all" ? control::GroupMode::kAll : control::GroupMode::kEnergyConscious;
  c.dt_s = s.dt();
  c.level2_period_s = s.control.level2_period_s;
  c.level2_defer_s = s.control.level2_defer_s;
  c.horizon = s.control.horizon;
  c.horizon_step_s = s.control.horizon_step_s;
  c.t_on_s = s.control.t_on_s;
  c.thermal_limit_s = s.control.thermal_limit_s;
  c.oracle = s.control.oracle;
  c.fault_detection = s.control.fault_detection;
  c.diagnosis.current_A = s.control.fault_current_A;
  c.diagnosis.jitter_V = s.control.fault_jitter_V;
  c.diagnosis.persistence_s = s.control.fault_persistence_s;
  c.diagnosis.probation_s = s.control.fault_probation_s;
  return c;
}
/// What group `side` reads from a tick.
control::GroupInput group_input(const msg::PlantTick& t, int side) {
  control::GroupInput in;
  in.tick = static_cast<long long>(t.tick());
  in.t = t.t();
  in.v_x = t.v_x();
  in.w = t.w();
  const msg::SideTick& own = t.sides()[side];
  in.phidot_side = own.phidot();
  in.phidot_ref_L = t.sides()[msg::SIDE_L].phidot_ref();
  in.phidot_ref_R = t.sides()[msg::SIDE_R].phidot_ref();
  in.battery_V = own.battery_V();
  in.live = own.live();
  in.active = own.active();
  in.n_other = own.relay_count();
  in.measured = !own.measured_A().empty();
  if (in.measured) {
    in.drives.phidot = own.phidot();
    in.drives.phidot_prev = own.phidot_prev();
    in.drives.agents.resize(own.measured_A().size());
    for (std::size_t j = 0; j < own.measured_A().size(); ++j) {
      control::DriveSample& d = in.drives.agents[j];
      d.drove = own.drove()[j] != 0;
      d.drive_V = own.drive_V()[j];
      d.measured_A = own.measured_A()[j];
      d.reported = own.reported()[j] != 0;
      d.reported_A = own.reported_A()[j];
    }
  }
  return in;
}

/// The Level-2 log record of a decision taken at this tick.
records::Level2Record level2_record(const control::GroupDecision& d) {
  records::Level2Record r;
  r.t_s = d.level2_t_s;
  r.n_live = d.n_live;
  r.n_other = d.level2_n_other;
  r.status = d.level2_status;
  r.relaxed = d.level2_relaxed;
  r.ipopt_n_active = d.ipopt_n_active;
  r.oracle_n_active = d.oracle_n_active;
  r.n_target = d.n_active;
  r.solve_ms = d.solve_time_ms;
  return r;
}
}  // namespace

namespace {
std::chrono::milliseconds level2_pause{0};
}  // namespace

void set_level2_pause(std::chrono::milliseconds pause) { level2_pause = pause; }

GroupNode::GroupNode(const comm::ProcessArgs& args, int side, std::shared_ptr<spdlog::logger> log)
    : args_(args),
      side_(side),
      log_(std::move(log)),
      ledger_path_(records::ledger_path(args.run_dir, side)),
      worker_(args.scenario.control.oracle, level2_pause),
      core_(side, make_config(args.scenario),
            records::load_ledger(ledger_path_, args.scenario.robot.per_side()), &worker_) {}

int GroupNode::run() {
  comm::TickFollower follower(args_, msg::NODE_GROUP, log_);
  follower.answer_writer<msg::GroupStatusPubSubType>(comm::topic::kGroup);
  if (level2_pause.count() > 0)
    log_->info("every Level-2 solve is followed by a {} ms pause (a slow solver, set_level2_pause)",
               level2_pause.count());
  if (core_.resumed())
    log_->info("resumed the wear ledger: {} decisions, {} reallocations so far", core_.ledger().decisions,
               core_.ledger().reallocations);
  // Every Level-2 decision, for the solve-time and oracle figures (appended: a restarted
  // controller continues the file).
  records::Level2LogWriter l2(records::level2_log_path(args_.run_dir, side_));
  bool infeasible = false;
  const int code = follower.run([&](const msg::PlantTick& t) {
    const control::GroupInput in = group_input(t, side_);
    const control::GroupDecision d = core_.step(in);
    if (d.ledger_due) records::save_ledger(ledger_path_, core_.ledger());
    if (d.level2_ran && (d.level2_status == control::kL2Infeasible) != infeasible) {
      infeasible = !infeasible;
      if (infeasible)
        log_->warn(
            "Level 2 infeasible at t={:.2f} s: {} live agents cannot hold the reference; all of them run",
            in.t, d.n_live);
      else
        log_->info("Level 2 feasible again at t={:.2f} s", in.t);
    }
    if (d.level2_ran && l2) l2.write(level2_record(d));
    msg::GroupStatus st;
    st.tick(t.tick());
    st.side(comm::to_msg_side(side_));
    st.active(d.active);
    st.live(in.live);
    st.wear_m(core_.ledger().wear_m);
    st.n_active(static_cast<uint16_t>(d.n_active));
    st.n_live(static_cast<uint16_t>(d.n_live));
    st.n_other(static_cast<uint16_t>(in.n_other));
    st.level2_status(to_msg_level2(d.level2_status));
    st.level2_relaxed(d.level2_relaxed);
    st.oracle_n_active(static_cast<int16_t>(d.oracle_n_active));
    st.solve_time_ms(d.solve_time_ms);
    st.decisions(d.decisions);
    st.reallocations(d.reallocations);
    st.faulty(d.faulty);
    for (const auto& ch : d.diagnosed) {
      const std::string name = config::agent_name(side_, ch.index);
      if (ch.flag == control::Diagnosis::kNone)
        log_->info("{} let back after its probation at t={:.2f} s", name, in.t);
      else
        log_->warn("{} isolated at t={:.2f} s: it looks {} (its measurements disagree with the motor model)", name,
                   in.t, control::diagnosis_name(ch.flag));
    }
    st.rejected(follower.rejected());
    follower.answer(st);
  });
  records::save_ledger(ledger_path_, core_.ledger());
  log_->info(
      "Level 2: {} decisions solved on the worker thread, {} of them waited for at the tick they were due",
      worker_.finished(), worker_.waited());
  log_->info("ledger saved: {} decisions, {} reallocations", core_.ledger().decisions,
             core_.ledger().reallocations);
  return code;
}

}  // namespace maptr::group
