#pragma once
// Level 1 of one agent (wheel-motor pair): from the tick the plant published, the voltage
// [V] to apply over [t_k, t_k+1]. Explicit time (ticks of dt_s), no DDS, no clock.
//   assigned by its group    -> PID on e = phidot_ref - phidot [rad/s], clamped to [0, V_B]
//                               ([-V_B, V_B] with a bidirectional driver: it can brake)
//   becoming active          -> the PID joins the side's running PIDs (Pid::align to the mean
//                               voltage they applied last tick), so the side's agents share the
//                               load evenly; with none active it starts at the back-EMF
//                               (zero current)
//   not assigned             -> open circuit (0 V, PID reset)
//   group silent (its status older than one tick): hold the last assignment for group_hold_s,
//                               then coast (open circuit)
//   central silent longer than central_timeout_s: ramp the last reference to zero at
//                               stop_decel_mps2 / r [rad/s^2] (a safe stop), still obeying the group
//   ticks skipped (the tick filter, comm/lockstep/tick_check.hpp: the agent was idle with a fresh group
//   and central in each, or it did not run yet): the agent goes on from tick k-1's speed and
//   reference carried in tick k, exactly as if it had stepped through them idle
#include <cstdint>
#include <vector>

#include "control/level1/pid.hpp"
#include "control/tunable.hpp"
#include "model/params.hpp"

namespace maptr::control {

enum class AgentState : uint8_t { kIdle = 0, kActive = 1, kHolding = 2, kCoasting = 3, kStopping = 4 };

/// The scenario's control.* fields the agent reads, declared here and nowhere else: the member
/// with its default, and its row in agent_tunables() (path, range, unit, description), which the
/// scenario's table takes as it is (control/tunable.hpp).
struct AgentTuning {
  PidGains pid;                    ///< control.kp, control.ki, control.kd
  double group_hold_s = 1.0;       ///< s a silent group's last assignment is held
  double central_timeout_s = 1.0;  ///< s of silence from central before the safe stop
  double stop_decel_mps2 = 2.0;    ///< deceleration of the safe stop, m/s^2
};

inline std::vector<Tunable<AgentTuning>> agent_tunables() {
  using T = AgentTuning;
  const auto closed = Bounds::closed;
  return {
      real_tunable<T>(
          "control.kp", [](T& t) -> double& { return t.pid.kp; }, closed(0, 1e6), "V s/rad",
          "wheel PID proportional gain (kp and ki not both zero); the paper's 0.5 and 2 leave a turn's yaw "
          "lagging (the run can end degraded: path not followed); the warehouse loop turns with kp 4, ki 20 "
          "(docs/MODEL.md \"Turning\")"),
      real_tunable<T>(
          "control.ki", [](T& t) -> double& { return t.pid.ki; }, closed(0, 1e6), "V/rad",
          "wheel PID integral gain (with kp: 20 for turns, see kp)"),
      real_tunable<T>(
          "control.kd", [](T& t) -> double& { return t.pid.kd; }, closed(0, 1e6), "V s^2/rad",
          "wheel PID derivative gain"),
      real_tunable<T>(
          "control.group_hold_s", [](T& t) -> double& { return t.group_hold_s; }, closed(0, 1e6), "s",
          "agents hold the last assignment this long without their group"),
      real_tunable<T>(
          "control.central_timeout_s", [](T& t) -> double& { return t.central_timeout_s; }, closed(0, 1e6),
          "s", "agents ramp to a stop after this long without central"),
      real_tunable<T>(
          "control.stop_decel_mps2", [](T& t) -> double& { return t.stop_decel_mps2; }, Bounds::above(0, 1e3),
          "m/s^2", "deceleration of that ramp"),
  };
}

/// The tuning and what the agent node knows of its robot and the run.
struct AgentConfig : AgentTuning {
  model::MotorParams motor;
  model::DriverParams driver;
  double wheel_radius_m = 0.035;  ///< r, m
  double dt_s = 0.01;             ///< tick period, s
};

/// What an agent reads from one tick (its own side's values).
struct AgentInput {
  long long tick = 0;
  double phidot_rad_s = 0.0;      ///< its wheel's speed
  double battery_V = 0.0;         ///< its group's battery voltage
  double side_active_V = 0.0;     ///< mean voltage its side's active agents applied last tick, 0 if none
  double phidot_ref_rad_s = 0.0;  ///< reference in force
  long long central_stamp = -1;   ///< tick of the central command in force
  bool assigned = false;          ///< its bit in the group's active mask
  long long group_stamp = -1;     ///< tick of the group status in force
  double phidot_prev_rad_s = 0.0;      ///< its wheel's speed at tick k-1 (for skipped ticks)
  double phidot_ref_prev_rad_s = 0.0;  ///< reference in force at tick k-1 (for skipped ticks)
};

struct AgentOutput {
  double voltage_V = 0.0;
  double current_A = 0.0;
  double efficiency = 0.0;
  AgentState state = AgentState::kIdle;
  bool drives() const {
    return state == AgentState::kActive || state == AgentState::kHolding || state == AgentState::kStopping;
  }
};

class AgentCore {
 public:
  explicit AgentCore(AgentConfig c);
  AgentOutput step(const AgentInput& in);

 private:
  AgentConfig c_;
  Pid pid_;
  bool last_assigned_ = false;
  bool was_driving_ = false;
  double stop_ref_ = 0.0;    ///< reference while stopping, rad/s
  double prev_error_ = 0.0;  ///< last tick's speed error, rad/s (tracked while idle too)
  bool has_prev_error_ = false;
  long long last_tick_ = -1;  ///< the tick stepped last, -1 before the first

  /// The state after idle steps through ticks up to k-1 (k = in.tick >= 1) that it did not take.
  void skip_to(const AgentInput& in);
};

}  // namespace maptr::control
