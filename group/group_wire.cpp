#include "group/group_wire.hpp"

#include "comm/side.hpp"

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

msg::GroupStatus group_status(const msg::PlantTick& t, int side, const control::GroupInput& in,
                              const control::GroupDecision& d, const control::Ledger& ledger) {
  msg::GroupStatus st;
  st.tick(t.tick());
  st.side(comm::to_msg_side(side));
  st.active(d.active);
  st.live(in.live);
  st.wear_m(ledger.wear_m);
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
  return st;
}

}  // namespace maptr::group
