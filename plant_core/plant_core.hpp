#pragma once
// Plant logic, free of DDS, clocks and files: owns the simulated time t_k = k * dt and the
// robot state, integrates one tick [t_k, t_k+1] at a time with the agents' voltages held
// (CVODE) and keeps the run's ledgers. Each tick returns what the run records contain: the
// trace row k (state at t_k, inputs over [t_k, t_k+1]) and each change of a side's set of
// driving agents; the caller writes them.
#include <cstdint>
#include <optional>
#include <vector>

#include "control/path.hpp"
#include "model/motor_fault.hpp"
#include "model/params.hpp"
#include "plant_core/fault_book.hpp"
#include "plant_core/integrator.hpp"
#include "plant_core/speed_band.hpp"

namespace maptr::plant_core {

/// What one agent applied over [t_k, t_k+1] (from its reply).
struct AgentApplied {
  bool replied = false;
  bool drives = false;
  double voltage_V = 0.0;
  double current_A = 0.0;
  double efficiency = 0.0;
  bool disconnected = false;  ///< its group isolated it: its motor's supply is open
};

/// What the drive measured of one agent (the groups' fault detection, control/diagnosis.hpp):
/// over the tick last integrated [t_{k-1}, t_k] and at its end t_k.
struct DriveMeasurement {
  bool drove = false;       ///< it replied driving
  double drive_V = 0.0;     ///< the voltage it said it applied (0 when not driving), V
  double measured_A = 0.0;  ///< current in its motor's lead at t_k, A
  bool reported = false;    ///< it replied
  double reported_A = 0.0;  ///< the current it reported (at t_{k-1}), A
};

/// What the plant core needs of a scenario (the node builds it).
struct PlantCoreConfig {
  model::RobotParams robot;
  double dt_s = 0.01;                  ///< tick length, s
  int trace_every = 1;                 ///< a trace row every this many ticks
  double initial_discharge_mAh = 0.0;  ///< charge already drawn from each battery at t = 0, mAh
  /// Speed shortfall below the reference that counts as a lost speed, % (0: never).
  double stop_below_speed_pct = 0.0;
  /// How long the shortfall must last to count as a lost speed, s.
  double speed_lost_hold_s = 5.0;
  /// Tracking error under which the reference counts as reached the first time, %.
  double reached_band_pct = kSpeedBandPct;
  /// The mission, whose path the robot's pose is measured against (control/path.hpp).
  control::Trajectory trajectory;
  /// The robot is measured against the path up to the reference's length plus this, m.
  double path_search_ahead_m = 2.0;
  /// The agents' own faults and clears (scenario actions fault and clear), at their ticks.
  std::vector<AgentFaultEvent> agent_faults;
  /// A group's flag this long after a clear still belongs to the cleared fault, s.
  double fault_grace_s = 0.0;
};

/// Trace row k: the state at t_k and what was applied over [t_k, t_k+1]. Per-side arrays are
/// indexed 0 = left, 1 = right.
struct TraceRow {
  long long tick = 0;
  double t_s = 0.0;
  model::State x{};
  double phidot_radps[2] = {0.0, 0.0};
  double ref_radps[2] = {0.0, 0.0};
  double voltage_mean_V[2] = {0.0, 0.0};   ///< mean over the driving agents (0 if none)
  double current_A[2] = {0.0, 0.0};        ///< sum over the driving agents
  double efficiency_mean[2] = {0.0, 0.0};  ///< mean over the driving agents (0 if none)
  double battery_V[2] = {0.0, 0.0};
  int n_active[2] = {0, 0};
  int n_live[2] = {0, 0};
  control::Pose reference;     ///< the path's reference pose at t_k
  double cross_track_m = 0.0;  ///< signed distance to the path at t_k (> 0: left of it), m
};

/// A side's set of driving agents changed at t_s (one flag per agent of the side).
struct AssignmentChange {
  double t_s = 0.0;
  int side = 0;
  std::vector<uint8_t> driving;
};

/// What one tick produced for the run records.
struct TickRecord {
  std::optional<TraceRow> row;  ///< empty when the tick is not traced (trace_every)
  std::vector<AssignmentChange> assignments;
};

class PlantCore {
 public:
  explicit PlantCore(const PlantCoreConfig& c);

  long long tick() const { return tick_; }
  double t() const { return tick_ * c_.dt_s; }
  const model::State& state() const { return x_; }
  double battery_V(int side) const;
  double phidot(int side) const;
  /// Mean voltage the active agents of a side applied over the last tick, V (0 if none).
  double active_voltage(int side) const { return active_V_[side]; }

  /// Integrates [t_k, t_k+1] with the applied inputs and advances k; returns trace row k and
  /// the assignment changes. ref_L/ref_R and the live counts are recorded only.
  /// Same as hold() then integrate().
  TickRecord advance(const std::vector<AgentApplied>& left, const std::vector<AgentApplied>& right,
                     double ref_L, double ref_R, int live_L, int live_R);
  /// First half of advance(): holds the inputs over [t_k, t_k+1], updates the ledgers and
  /// returns what tick k records (so that it can be written before an integration that may
  /// fail). Must be followed by integrate().
  TickRecord hold(const std::vector<AgentApplied>& left, const std::vector<AgentApplied>& right, double ref_L,
                  double ref_R, int live_L, int live_R);
  /// Second half of advance(): integrates [t_k, t_k+1] with the held inputs and advances k.
  /// Throws std::runtime_error on a CVODE failure.
  void integrate();

  // Ledgers for the summary.
  double mean_active_agents() const { return ticks_done_ ? active_sum_ / ticks_done_ : 0.0; }
  double max_speed_error_pct() const { return max_err_pct_; }
  double rms_speed_error_pct() const;
  bool reached_reference() const { return reached_; }
  /// True once the speed has stayed more than stop_below_speed_pct below its reference for
  /// speed_lost_hold_s (after having reached it); never when that option is 0.
  bool speed_lost() const { return speed_lost_; }
  /// Time each agent drove, s (index: side, agent).
  const std::vector<double>& active_time(int side) const { return active_time_[side]; }
  /// Charge drawn during the run (without the initial discharge), mAh.
  double drawn_mAh(int side) const;
  /// Kinetic energy of the robot now (translation, yaw, wheels), J; the run starts from rest.
  double kinetic_energy_J() const;
  int last_active(int side) const { return side == 0 ? last_active_L_ : last_active_R_; }
  /// How the robot has followed its path so far (the ticks held).
  const control::TrackingStats& tracking() const { return tracking_; }
  /// The agents' faults: in force, and the record of each.
  const FaultBook& faults() const { return book_; }
  /// A group's announced flags (its status of tick k, taken before integrate()): the flagged
  /// agents' motors are disconnected from then on.
  void on_group_flags(int side, const std::vector<uint8_t>& flags, const char* const* names, int n_names) {
    book_.on_flags(side, flags, t(), c_.dt_s, names, n_names);
  }
  /// What the drive measured of each agent of a side over the tick last integrated.
  const std::vector<DriveMeasurement>& measurements(int side) const { return measured_[side]; }

 private:
  struct SideSum {
    double v = 0, i = 0, eff = 0;
    int n = 0;
  };
  void hold_inputs(const std::vector<AgentApplied>* sides[2], SideSum sum[2]);
  SideSum held_[2];  ///< sums over the driving agents of the held tick
  TraceRow trace_row(const SideSum sum[2], double ref_L, double ref_R, int live_L, int live_R) const;
  void track_speed(double ref_v);
  void record_driving(std::vector<AssignmentChange>& out);

  PlantCoreConfig c_;
  CvodeIntegrator integ_;
  model::State x_{};
  model::Inputs u_;
  long long tick_ = 0;
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
  control::Path path_;
  control::TrackingStats tracking_;
  control::PathRef path_ref_;    ///< the reference at the tick held
  control::Projection path_at_;  ///< the robot against its path at the tick held
  FaultBook book_;
  std::vector<model::Winding> winding_[2];  ///< each motor's winding over the tick held
  std::vector<DriveMeasurement> measured_[2];
  void measure();
};

}  // namespace maptr::plant_core
