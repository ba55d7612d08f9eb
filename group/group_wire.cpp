#include "group/group_wire.hpp"

#include "comm/lockstep/side.hpp"
#include "comm/lockstep/wear_ledger.hpp"

namespace maptr::group {

namespace {
// The message's Level-2 statuses are the core's codes.
static_assert(msg::L2_NONE == control::kL2None && msg::L2_OK == control::kL2Ok &&
              msg::L2_INFEASIBLE == control::kL2Infeasible && msg::L2_SOLVER_FAILED == control::kL2Failed);

msg::Level2Status to_msg_level2(uint8_t s) {
  return s <= control::kL2Failed ? static_cast<msg::Level2Status>(s) : msg::L2_NONE;
}
}  // namespace

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

msg::GroupStatus group_status(const msg::PlantTick& t, int side, const control::GroupInput& in,
                              const control::GroupDecision& d, const control::Ledger& ledger) {
  msg::GroupStatus st;
  st.tick(t.tick());
  st.side(comm::to_msg_side(side));
  st.active(d.active);
  st.live(in.live);
  st.n_active(static_cast<uint16_t>(d.n_active));
  st.n_live(static_cast<uint16_t>(d.n_live));
  st.n_other(static_cast<uint16_t>(in.n_other));
  st.level2_status(to_msg_level2(d.level2.status));
  st.level2_relaxed(d.level2.relaxed);
  st.oracle_n_active(static_cast<int16_t>(d.level2.oracle_n_active));
  st.solve_time_ms(d.level2.solve_ms);
  st.ledger(comm::to_msg(ledger));
  st.faulty(d.faulty);
  return st;
}

std::optional<control::Ledger> kept_ledger(const msg::PlantTick& t, int side, long participant) {
  for (const msg::KeptLedger& k : t.ledgers()) {
    if (k.side() != comm::to_msg_side(side) ||
        (k.for_participant() != participant && k.for_participant() >= 0))
      continue;
    return comm::ledger_of(k.ledger(), k.assignment());
  }
  return std::nullopt;
}

control::Level2Decision level2_of(const msg::GroupStatus& st) {
  control::Level2Decision d;
  d.status = static_cast<uint8_t>(st.level2_status());
  d.relaxed = st.level2_relaxed();
  d.oracle_n_active = st.oracle_n_active();
  d.solve_ms = st.solve_time_ms();
  d.n_live = st.n_live();
  d.n_other = st.n_other();
  d.n_target = st.n_active();
  return d;
}

}  // namespace maptr::group
