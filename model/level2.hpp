#pragma once
// Level-2 energy-conscious operation (paper eq. "Efficiency", DESIGN "Control levels"):
// how many agents N_a of one group (side) should be active.
//
//   maximise   J(N_a) - c N_a,   J = sum_{h=0}^{H-1} eta[h],   eta = tau phidot / (V I_a)
//   subject to 1 <= N_a <= live,   V_req(N_a) <= V_B
// (eta of one active motor; all active motors of a side are identical.)
// c = agent_cost (1e-4 per agent) is a tie-break, not in the paper: where J is flat - a side
// that must brake (the inner side of a skid-steer turn needs a negative torque, the motors
// cannot brake, so every active motor idles at eta = 0 whatever N_a) - it makes "fewer agents"
// win, in the oracle and for Ipopt alike (a gradient of exactly 0 would leave Ipopt wherever
// it started). 1e-4 per agent over the horizon is 1e-5 of efficiency per step, far below any
// efficiency difference that matters, and above Ipopt's tolerance (1e-6) so the solver sees it.
//
// N_a is relaxed to a real number n (the paper solves the relaxed problem with SQP; the group
// uses Ipopt, group/core_level2.hpp). Because N_a is one small integer, exhaustive_level2()
// evaluates every integer and is the oracle the solver is tested against.
//
// Rollout (the "dynamics and motor equations" constraints of the paper, eliminated by
// simulation). It reuses the plant's model: the per-motor current and torque of motor.hpp and
// the rigid-body accelerations of dynamics.hpp body_forces(), with relaxed activation:
//   tau_side = n * active_torque(I_a, phidot) + (N_side - n) * inactive_torque(phidot)    [N m]
// N_side = RobotParams::per_side(): failed agents' wheels still roll and drag like inactive ones.
// Voltage model: each active motor applies what a well-tuned Level-1 speed loop would apply,
// the voltage giving the torque that makes the body approach the reference with a first-order
// time constant T_c (approach_time_s):
//   a_v = (v_ref - v_x)/T_c,  a_w = (w_ref - w)/T_c
//   tau_L + tau_R = r (m_eff a_v + F_rx),  tau_R - tau_L = (2 r / a)(I_eff a_w + M_r)
//   tau_a = (tau_side_needed - (N_side - n) inactive_torque) / n
//   V = clamp_s(voltage_for_torque(tau_a, phidot), 0, V_B)
// where clamp_s is a softplus-smoothed clamp (width clamp_smoothing_V; it differs from the
// hard clamp by less than 1e-6 V once the command is 0.3 V inside the limits), so that J is
// smooth in n for Ipopt. The voltage is recomputed every substep (substep_s, the rate of a
// Level-1 loop) and held over it (zero-order hold); the body (v_x, w) is integrated with
// classical RK4 per substep, the motor current following the speed inside the substep.
// eta of a substep is efficiency() of motor.hpp at the substep start; eta[h] is its mean over
// the substeps of step h, so 0 <= eta[h] <= 1 and 0 <= J <= H.
// The other side runs n_other active agents under the same voltage model (same battery
// voltage); n_other <= 0 means "not known yet" and the rollout assumes the other side makes
// the same choice n (symmetric straight-line assumption).
//
// Horizon step: H = 10 steps of step_s = 0.1 s cover exactly the 1 s between two Level-2
// decisions (the decision runs at 1 Hz): the choice is judged over the time it will be in force.
// 0.1 s is also well below T_c = 0.5 s, so the horizon resolves the approach transient.
//
// Feasibility: the steady-state voltage per active motor that holds (1 - speed_tolerance)
// times the reference must not exceed V_B (feasibility_voltage()); required_voltage() is the
// same steady state at an arbitrary fraction of the reference (1 = the reference itself).
// In steady state tau_L + tau_R = r F_rx and tau_R - tau_L = (2r/a) M_r, so the needed side
// torque does not depend on n_other; only the transient of the rollout does.
//
// Pure C++: no clocks, no logging, no solver; deterministic.
#include "model/params.hpp"

namespace maptr::model {

struct Level2Problem {
  RobotParams robot;
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
  double substep_s = 0.01;          ///< s, integration / voltage-update substep (<= step_s)
  double clamp_smoothing_V = 0.02;  ///< V, width of the smoothed voltage clamp
  double agent_cost = 1e-4;         ///< c, objective units per active agent (tie-break)

  /// Throws ParamError naming the field if the problem is malformed.
  void validate() const;
  /// Wheel speed reference of this side, rad/s.
  double phidot_ref_side() const { return side == 0 ? phidot_ref_L : phidot_ref_R; }
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

/// feasibility_voltage(p, n) <= battery_V.
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

}  // namespace maptr::model
