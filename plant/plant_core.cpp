#include "plant/plant_core.hpp"

#include <cmath>
#include <stdexcept>

#include "model/battery.hpp"

namespace maptr::plant {

PlantCore::PlantCore(const config::Scenario& s, const std::string& trace_path, const std::string& assignments_path)
    : s_(s), integ_(s.robot), u_(s.robot.per_side()) {
  x_[model::kChargeL] = x_[model::kChargeR] = s.initial_discharge_mAh;
  for (int side = 0; side < 2; ++side) active_time_[side].assign(s.robot.per_side(), 0.0);
  if (!assignments_path.empty()) {
    assignments_ = std::fopen(assignments_path.c_str(), "w");
    if (!assignments_) throw std::runtime_error("cannot write " + assignments_path);
    std::fprintf(assignments_, "t_s,side,driving\n");
  }
  trace_ = std::fopen(trace_path.c_str(), "w");
  if (!trace_) throw std::runtime_error("cannot write the trace " + trace_path);
  std::fprintf(trace_,
               "tick,t_s,x_m,y_m,theta_rad,v_x_mps,w_radps,phidot_L_radps,phidot_R_radps,ref_L_radps,ref_R_radps,"
               "V_L_mean_V,V_R_mean_V,I_L_A,I_R_A,eff_L,eff_R,battery_V_L,battery_V_R,discharge_L_mAh,"
               "discharge_R_mAh,n_active_L,n_active_R,n_live_L,n_live_R,energy_J,distance_m\n");
  std::fflush(trace_);
}

PlantCore::~PlantCore() {
  if (trace_) std::fclose(trace_);
  if (assignments_) std::fclose(assignments_);
}

double PlantCore::drawn_mAh(int side) const {
  return (side == 0 ? x_[model::kChargeL] : x_[model::kChargeR]) - s_.initial_discharge_mAh;
}

double PlantCore::battery_V(int side) const {
  return model::battery_voltage(s_.robot.battery, side == 0 ? x_[model::kChargeL] : x_[model::kChargeR]);
}

double PlantCore::phidot(int side) const {
  const double v = x_[model::kVx], w = x_[model::kW];
  const double vs = side == 0 ? v - 0.5 * s_.robot.track_m * w : v + 0.5 * s_.robot.track_m * w;
  return vs / s_.robot.wheel_radius_m;
}

double PlantCore::rms_speed_error_pct() const { return err_n_ ? std::sqrt(err_sq_sum_ / err_n_) : 0.0; }

void PlantCore::advance(const std::vector<AgentApplied>& left, const std::vector<AgentApplied>& right, double ref_L,
                        double ref_R, int live_L, int live_R) {
  struct SideSum {
    double v = 0, i = 0, eff = 0;
    int n = 0;
  } sum[2];
  const std::vector<AgentApplied>* sides[2] = {&left, &right};
  for (int s = 0; s < 2; ++s) {
    auto& volts = s == 0 ? u_.voltage_L : u_.voltage_R;
    auto& act = s == 0 ? u_.active_L : u_.active_R;
    for (std::size_t j = 0; j < act.size(); ++j) {
      const AgentApplied& a = (*sides[s])[j];
      act[j] = a.replied && a.drives ? 1 : 0;
      volts[j] = act[j] ? a.voltage_V : 0.0;
      if (act[j]) {
        sum[s].v += a.voltage_V;
        sum[s].i += a.current_A;
        sum[s].eff += a.efficiency;
        ++sum[s].n;
      }
    }
  }
  for (int s = 0; s < 2; ++s) active_V_[s] = sum[s].n ? sum[s].v / sum[s].n : 0.0;
  // Row k: state at t_k and what was applied over [t_k, t_k+1].
  if (tick_ % s_.trace_every == 0) {
    auto mean = [](double x, int n) { return n ? x / n : 0.0; };
    std::fprintf(trace_,
                 "%lld,%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.6g,%.6g,%.9g,%.9g,"
                 "%.9g,%.9g,%d,%d,%d,%d,%.9g,%.9g\n",
                 tick_, t(), x_[model::kX], x_[model::kY], x_[model::kTheta], x_[model::kVx], x_[model::kW],
                 phidot(0), phidot(1), ref_L, ref_R, mean(sum[0].v, sum[0].n), mean(sum[1].v, sum[1].n), sum[0].i,
                 sum[1].i, mean(sum[0].eff, sum[0].n), mean(sum[1].eff, sum[1].n), battery_V(0), battery_V(1),
                 x_[model::kChargeL], x_[model::kChargeR], sum[0].n, sum[1].n, live_L, live_R,
                 x_[model::kEnergyL] + x_[model::kEnergyR], x_[model::kDistance]);
    std::fflush(trace_);
  }
  const double ref_v = 0.5 * (ref_L + ref_R) * s_.robot.wheel_radius_m;
  if (ref_v > 0.0 && tick_ > 0) {
    // Tracking error once the reference has been reached the first time.
    const double err = 100.0 * std::fabs(x_[model::kVx] - ref_v) / ref_v;
    if (reached_ || err < 2.0) {
      reached_ = true;
      max_err_pct_ = std::max(max_err_pct_, err);
      err_sq_sum_ += err * err;
      ++err_n_;
    }
  }
  // Who drove over [t_k, t_k+1]: a row per change, and each agent's driving time.
  for (int side = 0; side < 2; ++side) {
    const auto& act = side == 0 ? u_.active_L : u_.active_R;
    for (std::size_t j = 0; j < act.size(); ++j)
      if (act[j]) active_time_[side][j] += s_.dt();
    if (assignments_ && act != last_drive_[side]) {
      std::string mask(act.size(), '0');
      for (std::size_t j = 0; j < act.size(); ++j)
        if (act[j]) mask[j] = '1';
      std::fprintf(assignments_, "%.6f,%c,%s\n", t(), side == 0 ? 'L' : 'R', mask.c_str());
      std::fflush(assignments_);
      last_drive_[side] = act;
    }
  }
  if (s_.stop_below_speed_pct > 0.0 && reached_ && ref_v > 0.0) {
    const double err = 100.0 * (ref_v - x_[model::kVx]) / ref_v;
    if (err > s_.stop_below_speed_pct) {
      if (below_since_ < 0.0) below_since_ = t();
      if (t() - below_since_ >= 5.0) speed_lost_ = true;
    } else {
      below_since_ = -1.0;
    }
  }
  integ_.step(x_, u_, t(), s_.dt());
  active_sum_ += sum[0].n + sum[1].n;
  last_active_L_ = sum[0].n;
  last_active_R_ = sum[1].n;
  ++ticks_done_;
  ++tick_;
}

}  // namespace maptr::plant
