#include "plant_core/plant_core.hpp"

#include <algorithm>
#include <cmath>

#include "model/battery.hpp"
#include "model/dynamics.hpp"
#include "model/kinematics.hpp"

namespace maptr::plant_core {

PlantCore::PlantCore(const PlantCoreConfig& c)
    : c_(c),
      integ_(c.robot),
      u_(c.robot.per_side()),
      path_(c.trajectory),
      book_(c.robot.per_side(), c.agent_faults, c.fault_grace_s) {
  x_[model::kChargeL] = x_[model::kChargeR] = c.initial_discharge_mAh;
  for (int side = 0; side < 2; ++side) {
    active_time_[side].assign(c.robot.per_side(), 0.0);
    winding_[side].assign(c.robot.per_side(), model::Winding{});
    measured_[side].assign(c.robot.per_side(), DriveMeasurement{});
  }
}

double PlantCore::drawn_mAh(int side) const {
  return (side == 0 ? x_[model::kChargeL] : x_[model::kChargeR]) - c_.initial_discharge_mAh;
}

double PlantCore::kinetic_energy_J() const {
  return model::kinetic_energy(c_.robot, x_[model::kVx], x_[model::kW]);
}

double PlantCore::battery_V(int side) const {
  return model::battery_voltage(c_.robot.battery, side == 0 ? x_[model::kChargeL] : x_[model::kChargeR]);
}

double PlantCore::phidot(int side) const {
  const model::WheelRates q =
      model::to_wheel_rates({x_[model::kVx], x_[model::kW]}, c_.robot.track_m, c_.robot.wheel_radius_m);
  return side == 0 ? q.phidot_L : q.phidot_R;
}

double PlantCore::rms_speed_error_pct() const { return err_n_ ? std::sqrt(err_sq_sum_ / err_n_) : 0.0; }

void PlantCore::hold_inputs(const std::vector<AgentApplied>* sides[2], SideSum sum[2]) {
  book_.apply(tick_, t());
  for (int s = 0; s < 2; ++s) {
    auto& volts = s == 0 ? u_.voltage_L : u_.voltage_R;
    auto& act = s == 0 ? u_.active_L : u_.active_R;
    auto& faults = s == 0 ? u_.fault_L : u_.fault_R;
    const auto& motor = book_.motor(s);
    if (book_.any_motor_fault(s))
      faults = motor;
    else
      faults.clear();
    const double battery = battery_V(s), floor = c_.robot.driver.floor_V(battery);
    for (std::size_t j = 0; j < act.size(); ++j) {
      const AgentApplied& a = (*sides[s])[j];
      const bool asked = a.replied && a.drives;
      // What the winding sees: the agent's voltage, unless its fault or its group says otherwise.
      const model::Winding w = model::winding(motor[j], asked, a.voltage_V, a.disconnected, floor, battery);
      winding_[s][j] = w;
      act[j] = w.conducts ? 1 : 0;
      volts[j] = w.conducts ? w.voltage_V : 0.0;
      DriveMeasurement& m = measured_[s][j];
      m.drove = asked;
      m.drive_V = asked ? a.voltage_V : 0.0;
      m.reported = a.replied;
      m.reported_A = a.replied ? a.current_A : 0.0;
      if (asked) {
        sum[s].v += a.voltage_V;
        sum[s].i += a.current_A;
        sum[s].eff += a.efficiency;
        ++sum[s].n;
      }
    }
  }
  for (int s = 0; s < 2; ++s) active_V_[s] = sum[s].n ? sum[s].v / sum[s].n : 0.0;
}

void PlantCore::measure() {
  for (int s = 0; s < 2; ++s) {
    const double w = phidot(s);
    const auto& motor = book_.motor(s);
    for (std::size_t j = 0; j < measured_[s].size(); ++j) {
      DriveMeasurement& m = measured_[s][j];
      m.measured_A = model::winding_current(c_.robot.motor, c_.robot.driver, motor[j], winding_[s][j], w);
      if ((m.drove || m.measured_A != 0.0) && !book_.disconnected(s, static_cast<int>(j)))
        book_.exposed(s, static_cast<int>(j));
    }
  }
}

TraceRow PlantCore::trace_row(const SideSum sum[2], double ref_L, double ref_R, int live_L,
                              int live_R) const {
  auto mean = [](double x, int n) { return n ? x / n : 0.0; };
  TraceRow r;
  r.tick = tick_;
  r.t_s = t();
  r.x = x_;
  r.ref_radps[0] = ref_L;
  r.ref_radps[1] = ref_R;
  r.n_live[0] = live_L;
  r.n_live[1] = live_R;
  r.reference = path_ref_.pose;
  r.cross_track_m = path_at_.cross_track;
  for (int s = 0; s < 2; ++s) {
    r.phidot_radps[s] = phidot(s);
    r.voltage_mean_V[s] = mean(sum[s].v, sum[s].n);
    r.current_A[s] = sum[s].i;
    r.efficiency_mean[s] = mean(sum[s].eff, sum[s].n);
    r.battery_V[s] = battery_V(s);
    r.n_active[s] = sum[s].n;
  }
  return r;
}

void PlantCore::track_speed(double ref_v) {
  if (ref_v > 0.0 && tick_ > 0) {
    // Tracking error once the reference has been reached the first time.
    const double err = 100.0 * std::fabs(x_[model::kVx] - ref_v) / ref_v;
    if (reached_ || err < c_.reached_band_pct) {
      reached_ = true;
      max_err_pct_ = std::max(max_err_pct_, err);
      err_sq_sum_ += err * err;
      ++err_n_;
    }
  }
}

void PlantCore::record_driving(std::vector<AssignmentChange>& out) {
  for (int side = 0; side < 2; ++side) {
    const auto& act = side == 0 ? u_.active_L : u_.active_R;
    for (std::size_t j = 0; j < act.size(); ++j)
      if (act[j]) active_time_[side][j] += c_.dt_s;
    if (act != last_drive_[side]) {
      out.push_back({t(), side, act});
      last_drive_[side] = act;
    }
  }
}

TickRecord PlantCore::advance(const std::vector<AgentApplied>& left, const std::vector<AgentApplied>& right,
                              double ref_L, double ref_R, int live_L, int live_R) {
  TickRecord rec = hold(left, right, ref_L, ref_R, live_L, live_R);
  integrate();
  return rec;
}

TickRecord PlantCore::hold(const std::vector<AgentApplied>& left, const std::vector<AgentApplied>& right,
                           double ref_L, double ref_R, int live_L, int live_R) {
  SideSum* sum = held_;
  sum[0] = sum[1] = SideSum{};
  const std::vector<AgentApplied>* sides[2] = {&left, &right};
  hold_inputs(sides, sum);
  const control::Pose pose{x_[model::kX], x_[model::kY], x_[model::kTheta]};
  path_ref_ = path_.at_time(t());
  path_at_ = path_.project(pose, path_ref_.s + c_.path_search_ahead_m);
  tracking_.add(t(), path_at_, path_ref_, pose);
  TickRecord rec;
  // Row k: state at t_k and what was applied over [t_k, t_k+1].
  if (tick_ % c_.trace_every == 0) rec.row = trace_row(sum, ref_L, ref_R, live_L, live_R);
  const double ref_v = model::body_from_rates({ref_L, ref_R}, c_.robot.track_m, c_.robot.wheel_radius_m).v_x;
  track_speed(ref_v);
  // Who drove over [t_k, t_k+1]: a record per change, and each agent's driving time.
  record_driving(rec.assignments);
  if (c_.stop_below_speed_pct > 0.0 && reached_ && ref_v > 0.0) {
    const double err = 100.0 * (ref_v - x_[model::kVx]) / ref_v;
    if (err > c_.stop_below_speed_pct) {
      if (below_since_ < 0.0) below_since_ = t();
      if (t() - below_since_ >= c_.speed_lost_hold_s) speed_lost_ = true;
    } else {
      below_since_ = -1.0;
    }
  }
  return rec;
}

void PlantCore::integrate() {
  integ_.step(x_, u_, t(), c_.dt_s);
  measure();
  active_sum_ += held_[0].n + held_[1].n;
  last_active_L_ = held_[0].n;
  last_active_R_ = held_[1].n;
  ++ticks_done_;
  ++tick_;
}

}  // namespace maptr::plant_core
