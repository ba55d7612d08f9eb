#pragma once
// Level 2: how many agents N_a of one side should be active (relaxed to a real n):
//   maximise   J(n) - c n,   J = sum_{h=0}^{H-1} eta[h]  (eta of one active motor, in [0, 1])
//   subject to 1 <= n <= live,   V_floor <= V_req(n) <= V_B  [V]
// (V_floor = 0, or -V_B with a bidirectional driver). A side whose steady demand is a braking
// torque (the inner side of a tight turn, with a bidirectional driver) runs every live agent:
// at low speed braking means driving against the motion (V < 0 < K_e phidot), whose battery
// power grows with the square of each motor's current, so the demand is best spread over all
// motors, and the fewest agents that can brake leave no margin (docs/MODEL.md "Level 2 in a
// turn" has the measurement).
// J comes from a rollout of the robot model over the horizon (H steps of step_s [s]) under a
// model of the speed loop; c = agent_cost is a tie-break. exhaustive_level2() evaluates every
// integer n and is the oracle the Ipopt solver (level2/solver.hpp) is tested against.
// docs/MODEL.md "Level 2" states the rollout, the voltage model and the feasibility in full.
#include "model/params.hpp"

namespace maptr::control {

struct Level2Problem {
  model::RobotParams robot;
  int side = 0;                     ///< 0 = left group, 1 = right group
  int live = 0;                     ///< live agents of this side: upper bound on N_a
  double n_other = 0.0;             ///< other side's active count (relayed); <= 0: unknown, use n
  double v_x = 0.0;                 ///< m/s, current body forward speed
  double w = 0.0;                   ///< rad/s, current yaw rate
  double phidot_ref_L = 0.0;        ///< rad/s, left wheel speed reference
  double phidot_ref_R = 0.0;        ///< rad/s, right wheel speed reference
  double battery_V = 23.4;          ///< V, supply limit of this side (the other side assumed equal)
  int horizon = 10;                 ///< H, steps
  double step_s = 0.1;              ///< s, horizon step (H * step_s = 1 s = the decision period)
  double speed_tolerance = 0.02;    ///< feasible if (1 - tol) * reference can be held
  double approach_time_s = 0.5;     ///< T_c, s, closed-loop time constant of the speed loop
  double substep_s = 0.02;          ///< s, integration / voltage-update substep (<= step_s)
  double clamp_smoothing_V = 0.02;  ///< V, width of the smoothed voltage clamp
  double agent_cost = 1e-4;         ///< c, objective units per active agent (tie-break)

  /// Throws ParamError naming the field if the problem is malformed.
  void validate() const;
};

/// J(n): sum over the H steps of one active motor's mean efficiency on this side, in [0, H].
/// n is real (relaxed); it is used as given (callers keep it in [1, live]).
double horizon_efficiency(const Level2Problem& p, double n_active);

/// The maximised objective: horizon_efficiency(p, n) - agent_cost * n.
double level2_objective(const Level2Problem& p, double n_active);

/// Steady-state voltage per active motor, V, that holds speed_scale times the reference
/// (both sides' wheel speeds scaled, so the turn radius is kept) with n active on this side:
///   V = K_e phidot + Omega ((tau_side + (N_side - n) b phidot) / n + b phidot) / K_T
///       + Omega I_0 sgn_s(phidot)
/// (voltage_for_torque() of motor.hpp at the needed per-motor torque).
double required_voltage(const Level2Problem& p, double n_active, double speed_scale = 1.0);

/// required_voltage at (1 - speed_tolerance) of the reference: the constraint's left side.
double feasibility_voltage(const Level2Problem& p, double n_active);

/// The net torque this side must give to hold the reference in steady state, N m.
double steady_side_torque(const Level2Problem& p);

/// True when the side's steady demand is a braking torque and the driver can brake: then every
/// live agent runs (exhaustive_level2() and the solver alike).
bool braking_demand(const Level2Problem& p);

/// driver floor <= feasibility_voltage(p, n) <= battery_V.
bool level2_feasible(const Level2Problem& p, double n_active);

struct Level2Choice {
  int n_active = 0;        ///< chosen N_a
  double objective = 0.0;  ///< level2_objective(n_active) = J - c n_active
  bool feasible = false;   ///< false: no n in [1, live] can hold the reference; n_active = live
};

/// The oracle: evaluates the objective J - c n at every integer n in [1, live]; among the
/// feasible ones takes the largest. Ties go to the smaller n (fewer agents worn, more spares for failures).
/// None feasible -> n_active = live, feasible = false. live <= 0 -> n_active = 0, infeasible.
Level2Choice exhaustive_level2(const Level2Problem& p);

}  // namespace maptr::control
