#include "deploy/top/fleet_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "group/group_wire.hpp"

namespace maptr::top {

namespace {

constexpr double kP99 = 0.99;

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

CellState from_reply(msg::AgentState s) {
  switch (s) {
    case msg::AGENT_ACTIVE:
      return CellState::kActive;
    case msg::AGENT_IDLE:
      return CellState::kIdle;
    case msg::AGENT_HOLDING:
      return CellState::kHolding;
    case msg::AGENT_COASTING:
      return CellState::kCoasting;
    case msg::AGENT_STOPPING:
      return CellState::kStopping;
  }
  return CellState::kUnknown;
}

}  // namespace

const char* state_name(CellState s) {
  switch (s) {
    case CellState::kActive:
      return "active";
    case CellState::kIdle:
      return "idle";
    case CellState::kHolding:
      return "holding";
    case CellState::kCoasting:
      return "coasting";
    case CellState::kStopping:
      return "stopping";
    case CellState::kDead:
      return "dead";
    case CellState::kPaused:
      return "paused";
    case CellState::kRejoining:
      return "rejoining";
    case CellState::kFaulty:
      return "faulty";
    case CellState::kUnknown:
      break;
  }
  return "?";
}

char state_letter(CellState s) {
  static const char kLetters[] = "?A.HCSXPRF";
  return kLetters[static_cast<int>(s)];
}

const char* phase_name(Phase p) {
  switch (p) {
    case Phase::kWaiting:
      return "waiting for the fleet";
    case Phase::kRunning:
      return "running";
    case Phase::kFinished:
      return "finished";
    case Phase::kAborted:
      return "aborted";
    case Phase::kGone:
      return "ended";
  }
  return "?";
}

FleetView::FleetView(RunInfo info) : info_(std::move(info)) {
  const int per_side = std::max(0, info_.agents / 2);
  for (auto& s : sides_) s.agents.assign(static_cast<std::size_t>(per_side), AgentCell{});
}

AgentCell* FleetView::cell(int side, int index) {
  if (side < 0 || side > 1 || index < 0) return nullptr;
  auto& a = sides_[side].agents;
  return static_cast<std::size_t>(index) < a.size() ? &a[static_cast<std::size_t>(index)] : nullptr;
}

void FleetView::add_event(const std::string& text, double t_s) {
  events_.push_back({t_s, text});
  while (events_.size() > kEventsKept) events_.pop_front();
}

void FleetView::set_recorded_events(std::vector<ViewEvent> events) {
  recorded_ = true;
  std::stable_sort(events.begin(), events.end(), [](const ViewEvent& a, const ViewEvent& b) { return a.t_s < b.t_s; });
  recorded_events_.assign(events.begin(), events.end());
}

void FleetView::release_recorded(double t) {
  while (!recorded_events_.empty() && !(recorded_events_.front().t_s > t + 1e-9)) {
    add_event(recorded_events_.front().text, recorded_events_.front().t_s);
    recorded_events_.pop_front();
  }
}

void FleetView::fold_side(int s, const msg::SideTick& st) {
  SideView& v = sides_[s];
  v.battery_V = st.battery_V();
  v.discharge_mAh = st.discharge_mAh();
  v.phidot = st.phidot();
  v.phidot_ref = st.phidot_ref();
  v.n_active = st.n_active();
  for (std::size_t i = 0; i < v.agents.size() && i < st.live().size(); ++i) {
    AgentCell& a = v.agents[i];
    a.live = st.live()[i] != 0;
    if (a.live) a.rejoining = false;
  }
}

void FleetView::on_tick(const msg::PlantTick& t, double arrival_s) {
  if (static_cast<long long>(t.tick()) <= tick_ && phase_ == Phase::kRunning) return;  // stale or repeated
  tick_ = static_cast<long long>(t.tick());
  t_s_ = t.t();
  v_x_ = t.v_x();
  w_ = t.w();
  energy_J_ = t.energy_J();
  distance_m_ = t.distance_m();
  for (int s = 0; s < 2; ++s) fold_side(s, t.sides()[s]);
  arrivals_.push_back({tick_, t_s_, arrival_s});
  while (arrivals_.size() > kRateWindowTicks) arrivals_.pop_front();
  if (phase_ == Phase::kWaiting) phase_ = Phase::kRunning;
  const bool last = t.run_state() == msg::RUN_FINISHED || t.run_state() == msg::RUN_ABORTED;
  release_recorded(last ? std::numeric_limits<double>::infinity() : t_s_);
  if (t.run_state() == msg::RUN_FINISHED && phase_ != Phase::kFinished) {
    phase_ = Phase::kFinished;
    add_event("run finished", t_s_);
  } else if (t.run_state() == msg::RUN_ABORTED && phase_ != Phase::kAborted) {
    phase_ = Phase::kAborted;
    add_event("run aborted", t_s_);
  }
}

void FleetView::on_reply(const msg::AgentReply& r, double arrival_s) {
  AgentCell* a = cell(static_cast<int>(r.side()), r.index());
  if (!a || static_cast<long long>(r.tick()) < a->reply_tick) return;
  a->reply_tick = static_cast<long long>(r.tick());
  a->reply_arrival_s = arrival_s;
  a->reply_state = r.state();
  a->voltage_V = r.voltage_V();
  a->current_A = r.current_A();
}

void FleetView::on_group(const msg::GroupStatus& g) {
  const int s = static_cast<int>(g.side());
  if (s < 0 || s > 1 || static_cast<long long>(g.tick()) < sides_[s].group_tick) return;
  SideView& v = sides_[s];
  v.group_heard = true;
  v.group_died = false;
  v.group_tick = static_cast<long long>(g.tick());
  v.level2 = group::level2_of(g);
  v.group_n_active = g.n_active();
  v.group_n_live = g.n_live();
  v.decisions = g.ledger().decisions();
  v.reallocations = g.ledger().reallocations();
  for (std::size_t i = 0; i < v.agents.size() && i < g.ledger().wear_m().size(); ++i)
    v.agents[i].wear_m = g.ledger().wear_m()[i];
  static const char* const kDiagnosis[] = {"", "open", "short", "torque", "resistance", "stuck", "sensor", "erratic", "liar"};
  for (std::size_t i = 0; i < v.agents.size() && i < g.faulty().size(); ++i) {
    const uint8_t f = g.faulty()[i] <= msg::DIAG_LIAR ? g.faulty()[i] : 0;
    if (f == v.agents[i].faulty) continue;
    v.agents[i].faulty = f;
    const std::string name = (s == 0 ? "L" : "R") + std::to_string(i);
    if (!recorded_)
      add_event(f ? name + " isolated by its group (" + kDiagnosis[f] + ")" : name + " let back by its group",
                ticked() ? t_s_ : std::nan(""));
  }
}

void FleetView::on_central(const msg::CentralCommand& c) { v_x_ref_ = c.v_x_ref(); }

void FleetView::on_membership(const msg::MembershipEvent& e, bool before_join) {
  const bool died = e.kind() == msg::MEMBER_DIED;
  static const char* const kKind[] = {" died", " started", " paused", " resumed"};
  const auto k = static_cast<std::size_t>(e.kind());
  if (!recorded_)
    add_event(e.name() + (k < 4 ? kKind[k] : " changed"), before_join || !ticked() ? std::nan("") : t_s_);
  // A pause or a resume leaves the process alive: only a death or a start changes the cell.
  if (e.kind() == msg::MEMBER_PAUSED || e.kind() == msg::MEMBER_RESUMED) return;
  if (e.node_kind() == msg::NODE_GROUP && (e.side() == msg::SIDE_L || e.side() == msg::SIDE_R))
    sides_[static_cast<int>(e.side())].group_died = died;
  if (e.node_kind() != msg::NODE_AGENT) return;
  AgentCell* a = cell(static_cast<int>(e.side()), e.index());
  if (!a) return;
  a->died = died;
  a->rejoining = !died;
}

void FleetView::on_gate(const msg::FaultGate& g) {
  if (recorded_) return;
  const auto it = gate_faults_.find(static_cast<long long>(g.tick()));
  add_event("scheduled " + (it == gate_faults_.end() ? std::string("fault") : it->second) + " (tick " +
                std::to_string(g.tick()) + ")",
            g.t());
}

void FleetView::on_ready(const msg::NodeReady& r) {
  if (!r.ready() || std::find(ready_.begin(), ready_.end(), r.name()) != ready_.end()) return;
  ready_.push_back(r.name());
}

void FleetView::on_summary(const std::string& status, const std::string& end_reason) {
  release_recorded(std::numeric_limits<double>::infinity());
  final_status_ = status;
  end_reason_ = end_reason;
  if (phase_ == Phase::kRunning || phase_ == Phase::kWaiting) phase_ = Phase::kGone;
}

void FleetView::on_fleet_gone() {
  if (phase_ != Phase::kRunning && phase_ != Phase::kWaiting) return;
  phase_ = Phase::kGone;
  add_event("fleet ended without a final tick", t_s_);
}

double FleetView::real_time_factor() const {
  if (arrivals_.size() < 2) return 0.0;
  const double wall = arrivals_.back().arrival_s - arrivals_.front().arrival_s;
  return wall > 0.0 ? (arrivals_.back().t_s - arrivals_.front().t_s) / wall : 0.0;
}

TickStats FleetView::tick_stats() const {
  std::vector<double> ms;
  for (std::size_t i = 1; i < arrivals_.size(); ++i)
    if (arrivals_[i].tick == arrivals_[i - 1].tick + 1)
      ms.push_back(1000.0 * (arrivals_[i].arrival_s - arrivals_[i - 1].arrival_s));
  return {percentile(ms, 0.5), percentile(ms, kP99), ms.size()};
}

double FleetView::speed_error_pct() const {
  return v_x_ref_ == 0.0 ? 0.0 : 100.0 * (v_x_ - v_x_ref_) / std::fabs(v_x_ref_);
}

CellState FleetView::state(int s, int index) const {
  const AgentCell& a = sides_[s].agents[static_cast<std::size_t>(index)];
  if (a.rejoining) return CellState::kRejoining;
  if (a.died || !a.live) return CellState::kDead;
  if (a.faulty) return CellState::kFaulty;
  if (a.reply_tick < 0) return CellState::kUnknown;
  if (phase_ == Phase::kRunning && now_s_ - a.reply_arrival_s > kPausedAfter_s) return CellState::kPaused;
  return from_reply(a.reply_state);
}

int FleetView::count(CellState st) const {
  int n = 0;
  for (int s = 0; s < 2; ++s)
    for (std::size_t i = 0; i < sides_[s].agents.size(); ++i)
      n += state(s, static_cast<int>(i)) == st ? 1 : 0;
  return n;
}

int FleetView::live_agents() const {
  return info_.agents - count(CellState::kDead) - count(CellState::kRejoining);
}

bool FleetView::group_silent(int s) const {
  const SideView& v = sides_[s];
  return v.group_died || !v.group_heard || tick_ - v.group_tick > kGroupSilentTicks;
}

}  // namespace maptr::top
