#include "idl/rules.hpp"

#include <algorithm>
#include <cmath>

namespace maptr::msg {

namespace {
bool finite_all(std::initializer_list<double> v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}
/// One entry of 0 or 1 per agent of a side.
bool mask(const std::vector<uint8_t>& m, std::size_t per_side) {
  if (m.size() != per_side) return false;
  for (uint8_t x : m)
    if (x > 1) return false;
  return true;
}
bool name_ok(const std::string& n) { return !n.empty() && n.size() <= kMaxNameLength; }
/// V_active is the mean of tick k-1's voltages (negative when an H-bridge brakes), clamped to
/// that tick's battery voltage; the battery's voltage at t_k may be a little lower.
constexpr double kVoltageMargin = 1.01;

/// The drive's measurements: all absent, or one finite entry per agent.
bool measurements(const SideTick& s, std::size_t per_side) {
  if (s.drove().empty() && s.drive_V().empty() && s.measured_A().empty() && s.reported().empty() &&
      s.reported_A().empty())
    return true;
  if (!mask(s.drove(), per_side) || !mask(s.reported(), per_side) || s.drive_V().size() != per_side ||
      s.measured_A().size() != per_side || s.reported_A().size() != per_side)
    return false;
  for (std::size_t i = 0; i < per_side; ++i)
    if (!std::isfinite(s.drive_V()[i]) || !std::isfinite(s.measured_A()[i]) || !std::isfinite(s.reported_A()[i]))
      return false;
  return true;
}

bool side_tick(const SideTick& s, std::size_t per_side) {
  return finite_all({s.phidot(), s.battery_V(), s.discharge_mAh(), s.phidot_ref(), s.V_active(),
                     s.phidot_prev(), s.phidot_ref_prev()}) &&
         mask(s.active(), per_side) && mask(s.live(), per_side) && mask(s.wake(), per_side) &&
         s.battery_V() >= 0 && s.V_active() >= -kVoltageMargin * s.battery_V() && s.n_active() <= per_side && s.relay_count() <= per_side &&
         s.group_stamp() >= -1 && measurements(s, per_side);
}
/// A ledger of `n` agents: distances and active times finite and not negative, times finite, a
/// Level-2 choice of at most n.
bool ledger(const WearLedger& l, std::size_t n) {
  if (l.wear_m().size() != n || l.active_time_s().size() != n || l.n_target() > n) return false;
  for (const auto* v : {&l.wear_m(), &l.active_time_s()})
    for (double x : *v)
      if (!std::isfinite(x) || x < 0.0) return false;
  return finite_all({l.last_t(), l.last_alloc_t()});
}

}  // namespace

bool well_formed(const PlantTick& t, const FleetBounds& b) {
  if (!finite_all({t.t(), t.x(), t.y(), t.theta(), t.v_x(), t.w(), t.energy_J(), t.distance_m()}))
    return false;
  if (t.run_state() > RUN_ABORTED || t.central_stamp() < -1) return false;
  for (const SideTick& s : t.sides())
    if (!side_tick(s, b.per_side)) return false;
  for (const KeptLedger& k : t.ledgers())
    if (k.side() > SIDE_R || !mask(k.assignment(), b.per_side) || !ledger(k.ledger(), b.per_side))
      return false;
  return t.paused().empty() || mask(t.paused(), 2 * b.per_side + 3);
}

bool well_formed(const AgentReply& r, const FleetBounds& b) {
  return r.side() <= SIDE_R && r.index() < b.per_side &&
         finite_all({r.voltage_V(), r.current_A(), r.efficiency()}) &&
         r.state() <= AGENT_STOPPING && r.pid() != 0;
}

bool well_formed(const GroupStatus& g, const FleetBounds& b) {
  const std::size_t n = b.per_side;
  if (g.side() > SIDE_R || !mask(g.active(), n) || !mask(g.live(), n) || !ledger(g.ledger(), n)) return false;
  if (!g.faulty().empty() && g.faulty().size() != n) return false;
  for (uint8_t f : g.faulty())
    if (f > DIAG_LIAR) return false;
  if (g.n_active() > n || g.n_live() > n || g.n_other() > n || g.level2_status() > L2_SOLVER_FAILED)
    return false;
  const double relaxed = g.level2_relaxed();
  return std::isfinite(relaxed) && relaxed >= 0.0 && relaxed <= static_cast<double>(n) &&
         g.oracle_n_active() >= -1 && g.oracle_n_active() <= static_cast<int>(n) &&
         std::isfinite(g.solve_time_ms()) && g.solve_time_ms() >= 0.0;
}

bool well_formed(const CentralCommand& c, const FleetBounds& b) {
  if (!finite_all({c.v_x_ref(), c.w_ref()}) || std::fabs(c.v_x_ref()) >= b.v_bound_mps ||
      std::fabs(c.w_ref()) >= b.w_bound_radps)
    return false;
  for (double ref : c.phidot_ref())
    if (!std::isfinite(ref) || std::fabs(ref) >= b.ref_bound_radps) return false;
  // A relayed count is the other side's active agents: at most a side's agents.
  for (unsigned short n : c.relay_count_for())
    if (n > b.per_side) return false;
  return true;
}

bool well_formed(const MembershipEvent& e, const FleetBounds& b) {
  if (e.seq() == 0 || !name_ok(e.name()) || e.node_kind() > NODE_PLANT || e.side() > SIDE_R ||
      e.kind() > MEMBER_RESUMED || !std::isfinite(e.wall_s()) || e.wall_s() < 0.0)
    return false;
  if (e.participant_id() < -1 || e.participant_id() > 65535) return false;
  return e.node_kind() != NODE_AGENT || e.index() < b.per_side;
}

bool well_formed(const Control& c) {
  return c.command() > CONTROL_NONE && c.command() <= CONTROL_GATE_OPEN && c.seq() > 0;
}

bool well_formed(const FaultGate& g) { return std::isfinite(g.t()) && g.t() >= 0.0; }

bool well_formed(const NodeReady& r) {
  if (!name_ok(r.name()) || r.kind() > NODE_PLANT || r.pid() == 0) return false;
  if (r.unmatched().size() > kMaxUnmatched || (r.ready() && !r.unmatched().empty())) return false;
  return std::all_of(r.unmatched().begin(), r.unmatched().end(), name_ok);
}

}  // namespace maptr::msg
