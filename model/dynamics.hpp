#pragma once
// The plant's derivative function (paper Sec. 3, corrected as docs/MODEL.md lists), for any N.
//
//   (m + N I_w / r^2) dv_x/dt            = (tau_L + tau_R) / r - F_rx
//   (I_zz + N I_w a^2 / (4 r^2)) dw/dt   = (a/2)(tau_R - tau_L) / r - M_r
//   dX/dt = v_x cos(theta), dY/dt = v_x sin(theta), dtheta/dt = w
// tau_side = sum over the side's motors (active: DC motor model; inactive: -b phidot).
// Rolling, per wheel:  F_s = mu_s (m g / N) (2/pi) atan(k_s v_side)   (summed into F_rx;
//   the left/right difference gives the yaw moment (a/2)(F_R - F_L)).
// Lateral, per wheel of row j at x_j: F_l = mu_l (m g / N) (2/pi) atan(k_s w x_j),
//   M_lat = sum_j F_l x_j (4 wheels per row).
// Integrated ledgers (all explicit states, so that CVODE integrates them too):
//   energy drawn per side (J), discharge per side (mAh), path length per side (m),
//   distance (m), Joule losses, mechanical losses, back-emf/torque-constant mismatch losses (J).
#include <array>
#include <cstdint>
#include <vector>

#include "model/motor_fault.hpp"
#include "model/params.hpp"

namespace maptr::model {

enum StateIndex : int {
  kX = 0,      ///< m, world
  kY,          ///< m, world
  kTheta,      ///< rad
  kVx,         ///< m/s, body forward speed
  kW,          ///< rad/s, yaw rate
  kEnergyL,    ///< J drawn from the left battery
  kEnergyR,    ///< J
  kChargeL,    ///< mAh drawn from the left battery
  kChargeR,    ///< mAh
  kPathL,      ///< m, integral of |v_L|
  kPathR,      ///< m, integral of |v_R|
  kDistance,   ///< m, integral of |v_x|
  kLossJoule,  ///< J, electrical: I^2 R in the windings + braking power the driver dissipates
  kLossMech,   ///< J, ground friction + motor friction + viscous drag
  kLossEmf,    ///< J, (K_e - K_T) I phidot (the datasheet's K_e != K_T)
  kStateSize
};

using State = std::array<double, kStateSize>;

/// Inputs held over one tick (zero-order hold): each agent's voltage and activation.
/// Index i of side s is agent s<i>; voltage of an inactive agent is ignored. A motor's fault
/// (model/motor_fault.hpp) changes how an active one turns its voltage into current and torque;
/// open circuits and stuck drivers are already in active and voltage (model::winding()).
struct Inputs {
  std::vector<double> voltage_L, voltage_R;  ///< V
  std::vector<uint8_t> active_L, active_R;   ///< 1 = motor driven, 0 = free-wheeling
  std::vector<MotorFault> fault_L, fault_R;  ///< empty: every motor of the side healthy

  explicit Inputs(int per_side = 0)
      : voltage_L(per_side, 0.0), voltage_R(per_side, 0.0), active_L(per_side, 0), active_R(per_side, 0) {}
};

/// Per-side quantities at one instant (for diagnostics and the agents' current/efficiency).
struct SideLoad {
  double torque_Nm = 0.0;  ///< net shaft torque of the side's motors
  double current_A = 0.0;  ///< battery current: drawn (> 0), or charging with regeneration (< 0)
  double power_W = 0.0;    ///< battery power: drawn (> 0), or charging with regeneration (< 0)
  double joule_W = 0.0;    ///< I^2 R of the windings + driver_W
  double driver_W = 0.0;   ///< braking power the driver dissipates (not returned to the battery)
  double motor_loss_W = 0.0;  ///< motor friction + viscous dissipation
  double emf_loss_W = 0.0;
};

/// One side's motors at wheel speed phidot. A motor that drives (V I_a >= 0) draws |I_a| from
/// the battery at power V I_a. One that brakes (V I_a < 0) hands -V I_a to the driver, which
/// dissipates it, or with regeneration charges the battery with it, up to charge_limit_A of
/// the side's summed braking current (the share above the limit is dissipated).
/// A faulted motor's share: torque=F and resistance=F with their parameters; a shorted one
/// (fault short, active at 0 V) carries -K_e phidot / Omega through the short, heating its winding
/// and drawing nothing from the battery. faults empty: all healthy.
SideLoad side_load(const MotorParams& m, const DriverParams& d, const std::vector<double>& voltage,
                   const std::vector<uint8_t>& active, double phidot_rad_s,
                   const std::vector<MotorFault>& faults = {});

/// Effective inertias of the robot with its N wheels (wheel inertia I_w seen at the body):
///   m_eff = m + N I_w / r^2  [kg],   I_eff = I_zz + N I_w a^2 / (4 r^2)  [kg m^2].
struct EffectiveInertia {
  double mass_kg = 0.0;
  double yaw_kgm2 = 0.0;
};
EffectiveInertia effective_inertia(const RobotParams& p);

/// Rigid-body part of the dynamics for given net side torques (shared by the plant's
/// derivative and by the Level-2 rollout, so both use one model).
struct BodyForces {
  double dv_x = 0.0;           ///< m/s^2
  double dw = 0.0;             ///< rad/s^2
  double f_rx = 0.0;           ///< N, longitudinal resistance
  double m_r = 0.0;            ///< N m, resisting yaw moment
  double ground_loss_W = 0.0;  ///< power dissipated by rolling and lateral friction
};
BodyForces body_forces(const RobotParams& p, double tau_L_Nm, double tau_R_Nm, double v_x, double w);

/// body_forces() in two parts, for callers that apply several torques at one state (the
/// Level-2 rollout): the resistances at (v_x, w) (f_rx, m_r, ground_loss_W; dv_x and dw left
/// 0), then the accelerations under given torques against them. Composed, they are
/// body_forces() to the last bit.
BodyForces body_resistances(const RobotParams& p, double v_x, double w);
BodyForces with_torques(const RobotParams& p, const EffectiveInertia& in, const BodyForces& resistances,
                        double tau_L_Nm, double tau_R_Nm);

/// Derivative of the state; dx must have kStateSize entries. Pure function.
void derivative(const RobotParams& p, const Inputs& u, const double* x, double* dx);

/// Kinetic energy of the robot (translation, yaw, wheels), J.
double kinetic_energy(const RobotParams& p, double v_x, double w);

/// Longitudinal resistance F_rx at a straight-line speed v (w = 0), N.
double rolling_resistance(const RobotParams& p, double v);

}  // namespace maptr::model
