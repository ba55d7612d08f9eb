#pragma once
// Plant logic, free of DDS: owns the simulated time and the robot state, integrates one tick
// at a time with the agents' voltages held (CVODE), writes the trace as it goes (flushed per
// row, so an aborted run keeps what it produced) and keeps the run's ledgers.
#include <cstdio>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "plant/integrator.hpp"

namespace maptr::plant {

/// What one agent applied over [t_k, t_k+1] (from its reply).
struct AgentApplied {
  bool replied = false;
  bool drives = false;
  double voltage_V = 0.0;
  double current_A = 0.0;
  double efficiency = 0.0;
};

class PlantCore {
 public:
  /// Writes the trace to trace_path and, when assignments_path is not empty, one row per
  /// change of the set of driving agents to assignments_path.
  PlantCore(const config::Scenario& s, const std::string& trace_path, const std::string& assignments_path = "");
  ~PlantCore();
  PlantCore(const PlantCore&) = delete;
  PlantCore& operator=(const PlantCore&) = delete;

  long long tick() const { return tick_; }
  double t() const { return tick_ * s_.dt(); }
  const model::State& state() const { return x_; }
  double battery_V(int side) const;
  double phidot(int side) const;
  /// Mean voltage the active agents of a side applied over the last tick, V (0 if none).
  double active_voltage(int side) const { return active_V_[side]; }

  /// Integrates [t_k, t_k+1] with the applied inputs, writes trace row k, advances k.
  /// ref_L/ref_R and live counts are recorded in the trace only.
  void advance(const std::vector<AgentApplied>& left, const std::vector<AgentApplied>& right, double ref_L,
               double ref_R, int live_L, int live_R);

  // Ledgers for the summary.
  double mean_active_agents() const { return ticks_done_ ? active_sum_ / ticks_done_ : 0.0; }
  double max_speed_error_pct() const { return max_err_pct_; }
  double rms_speed_error_pct() const;
  bool reached_reference() const { return reached_; }
  /// True once the speed has stayed more than stop_below_speed_pct below its reference for 5 s
  /// (after having reached it); never when that option is 0.
  bool speed_lost() const { return speed_lost_; }
  /// Time each agent drove, s (index: side, agent).
  const std::vector<double>& active_time(int side) const { return active_time_[side]; }
  /// Charge drawn during the run (without the initial discharge), mAh.
  double drawn_mAh(int side) const;
  int last_active(int side) const { return side == 0 ? last_active_L_ : last_active_R_; }

 private:
  config::Scenario s_;
  CvodeIntegrator integ_;
  model::State x_{};
  model::Inputs u_;
  long long tick_ = 0;
  std::FILE* trace_ = nullptr;
  std::FILE* assignments_ = nullptr;
  std::vector<uint8_t> last_drive_[2];
  double active_V_[2] = {0.0, 0.0};
  std::vector<double> active_time_[2];
  double below_since_ = -1.0;
  bool speed_lost_ = false;
  long long ticks_done_ = 0;
  double active_sum_ = 0.0;
  double max_err_pct_ = 0.0, err_sq_sum_ = 0.0;
  long long err_n_ = 0;
  int last_active_L_ = 0, last_active_R_ = 0;
  bool reached_ = false;
};

}  // namespace maptr::plant
