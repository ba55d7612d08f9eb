#include "control/group_core.hpp"

#include <algorithm>
#include <cmath>

#include "control/level2/problem.hpp"
#include "control/level3/allocation.hpp"

namespace maptr::control {

namespace {
/// s: a period counts as elapsed this close to its end (tick times carry rounding).
constexpr double kTimeSlackS = 1e-9;

int count(const std::vector<uint8_t>& m) { return static_cast<int>(std::count(m.begin(), m.end(), 1)); }
}  // namespace

GroupCore::GroupCore(int side, const GroupConfig& config, std::optional<Ledger> resume, Level2Runner* runner)
    : side_(side),
      c_(config),
      ledger_(resume ? std::move(*resume) : Ledger(config.robot.per_side())),
      own_runner_(runner ? nullptr : std::make_unique<InlineLevel2Runner>(config.oracle)),
      runner_(runner ? runner : own_runner_.get()),
      defer_ticks_(std::llround(config.level2_defer_s / config.dt_s)) {
  if (config.fault_detection) {
    DiagnosisConfig dc;
    static_cast<DiagnosisTuning&>(dc) = config;
    dc.motor = config.robot.motor;
    dc.driver = config.robot.driver;
    dc.dt_s = config.dt_s;
    diagnosis_.emplace(config.robot.per_side(), dc);
  }
  resumed_ = resume.has_value();
}

bool GroupCore::update_cruise(const GroupInput& in) {
  const double ref = side_ == 0 ? in.phidot_ref_L : in.phidot_ref_R;
  const double err = ref > 0.0 ? std::fabs(in.phidot_side - ref) / ref : 1.0;
  if (err <= c_.cruise_enter) cruise_ = true;
  if (err > c_.cruise_leave) cruise_ = false;
  return cruise_;
}

void GroupCore::start_level2(const GroupInput& in, GroupDecision& d, int& target) {
  Level2Problem p;
  p.robot = c_.robot;
  p.side = side_;
  p.live = d.n_live;
  p.n_other = in.n_other;
  p.v_x = in.v_x;
  p.w = in.w;
  p.phidot_ref_L = in.phidot_ref_L;
  p.phidot_ref_R = in.phidot_ref_R;
  p.battery_V = in.battery_V;
  p.horizon = c_.horizon;
  p.step_s = c_.horizon_step_s;
  if (p.live <= 0) {  // nothing to solve: decided at once
    target = 0;
    d.level2.status = kL2Infeasible;
    ++ledger_.decisions;
    return;
  }
  runner_->start(p);
  pending_ = Pending{in.tick + defer_ticks_, in.t, in.n_other, false};
}

void GroupCore::apply_level2(GroupDecision& d, int& target) {
  const Level2Outcome o = runner_->finish();
  const Pending p = *pending_;
  pending_.reset();
  if (p.stale) return;
  const Level2Result& r = o.result;
  d.level2_ran = true;
  d.level2.t_s = p.t_s;
  d.level2.n_live = d.n_live;
  d.level2.n_other = p.n_other;
  d.level2.status = !r.feasible ? kL2Infeasible : r.ipopt_status >= 0 ? kL2Ok : kL2Failed;
  d.level2.relaxed = r.n_relaxed;
  d.level2.ipopt_n_active = r.n_active;
  d.level2.oracle_n_active = o.oracle_n_active;
  d.level2.solve_ms = r.solve_time_ms;
  target = r.feasible ? r.n_active : d.n_live;
  ++ledger_.decisions;
}

int GroupCore::decide_count(const GroupInput& in, bool cruising, GroupDecision& d, bool& realloc,
                            const std::vector<uint8_t>& next) {
  // No decision yet (n_target 0, e.g. cruising from the start): every live agent runs until one is applied.
  int target = ledger_.n_target > 0 ? ledger_.n_target : d.n_live;
  if (!cruising) {
    // Accelerating, braking or recovering: every live agent helps.
    target = d.n_live;
    realloc = next != in.live;
    last_l2_t_ = kNeverS;  // decide as soon as cruise is reached
    if (pending_) pending_->stale = true;
  } else if (!pending_ && in.t - last_l2_t_ >= c_.level2_period_s - kTimeSlackS) {
    last_l2_t_ = in.t;
    start_level2(in, d, target);
  }
  if (pending_ && in.tick >= pending_->apply_tick) apply_level2(d, target);
  return std::min(target, d.n_live);
}

void GroupCore::accrue_wear(const GroupInput& in) {
  // The assignment in force over [t_{k-1}, t_k] drove |v_side| dt each.
  if (ledger_.last_t >= 0.0 && in.t > ledger_.last_t) {
    const double dt = in.t - ledger_.last_t;
    ledger_.accrue(in.active, std::fabs(in.phidot_side) * c_.robot.wheel_radius_m * dt, dt);
  }
  ledger_.last_t = in.t;
}

GroupDecision GroupCore::step(const GroupInput& measured_in) {
  const int n = c_.robot.per_side();
  // Faulty agents first: from here on a flagged agent is not live.
  GroupInput in = measured_in;
  std::vector<DiagnosisChange> diagnosed;
  if (diagnosis_ && in.measured) diagnosed = diagnosis_->step(in.t, in.drives);
  if (diagnosis_)
    for (int j = 0; j < n; ++j)
      if (diagnosis_->flags()[static_cast<std::size_t>(j)]) in.live[static_cast<std::size_t>(j)] = 0;
  accrue_wear(in);

  GroupDecision d = last_;  // the last solve's diagnostics stay on the status topic
  d.level2_ran = false;
  d.n_live = count(in.live);
  std::vector<uint8_t> next = ledger_.assignment;
  for (int j = 0; j < n; ++j)
    if (!in.live[j]) next[j] = 0;

  if (c_.mode == GroupMode::kAll) {
    next = in.live;
    d.level2.status = kL2None;
  } else {
    bool realloc = false;
    const int target = decide_count(in, update_cruise(in), d, realloc, next);
    bool overheated = false;
    for (int j = 0; j < n; ++j)
      if (next[j] && ledger_.active_time_s[j] >= c_.thermal_limit_s) overheated = true;
    realloc = realloc || target != ledger_.n_target || count(next) != target || overheated ||
              in.t - ledger_.last_alloc_t >= c_.t_on_s - kTimeSlackS;
    ledger_.n_target = target;
    if (realloc) {
      AllocationInput ai;
      ai.distance_m = ledger_.wear_m;
      ai.live = in.live;
      ai.active_time_s = ledger_.active_time_s;
      ai.thermal_limit_s = c_.thermal_limit_s;
      ai.n_active = target;
      next = allocate(ai);
      ledger_.last_alloc_t = in.t;
      ++ledger_.reallocations;
    }
  }
  ledger_.assignment = next;
  d.active = next;
  d.n_active = count(next);
  if (d.level2_ran) d.level2.n_target = d.n_active;  // what the side runs from the decision on
  d.decisions = ledger_.decisions;
  d.reallocations = ledger_.reallocations;
  d.faulty = diagnosis_ ? diagnosis_->flags() : std::vector<uint8_t>(static_cast<std::size_t>(n), 0);
  last_ = d;
  d.diagnosed = std::move(diagnosed);
  return d;
}

}  // namespace maptr::control
