#pragma once
// DC motor of one agent (paper eq. motor1, corrected; docs/MODEL.md "Motor" and "Driver").
//   active:   I_a = (V - K_e phidot) / Omega                   [A]   (bidirectional driver)
//             I_a = max(0, (V - K_e phidot) / Omega)           [A]   (unidirectional: no braking)
//             tau = K_T (I_a - I_0 sgn_s(phidot)) - b phidot   [N m] (K_T I_0 is friction)
//   inactive: open circuit, I_a = 0, tau = -b phidot           [N m]
// sgn_s(x) = tanh(x / friction_sign_scale): a smooth sign that vanishes at standstill.
#include "model/params.hpp"

namespace maptr::model {

/// Smooth sign used for Coulomb-like motor friction.
double smooth_sign(double phidot_rad_s, double scale_rad_s);

/// Armature current of an active motor, A: of either sign with a bidirectional driver, never
/// negative with a unidirectional one.
double armature_current(const MotorParams& m, const DriverParams& d, double voltage_V, double phidot_rad_s);

/// Net shaft torque of an active motor at the given current and speed, N m.
double active_torque(const MotorParams& m, double current_A, double phidot_rad_s);

/// Net shaft torque of an inactive (free-wheeling) motor, N m.
double inactive_torque(const MotorParams& m, double phidot_rad_s);

/// Net torque of a side whose n_active of n_side motors are active at current I each (the
/// others inactive), all at speed phidot, N m; n_active may be real (the relaxed Level 2):
///   tau_side = n_active active_torque(I, phidot) + (n_side - n_active) inactive_torque(phidot)
double side_torque(const MotorParams& m, double n_active, double n_side, double current_A,
                   double phidot_rad_s);

/// Torque each of n_active active motors must give for the side's net torque to be
/// tau_side_Nm (the inverse of side_torque in the active torque), N m.
double torque_per_active(const MotorParams& m, double tau_side_Nm, double n_active, double n_side,
                         double phidot_rad_s);

/// Efficiency of an active motor: driving (V I > 0 and tau phidot > 0) tau phidot / (V I);
/// braking with regeneration (V I < 0 and tau phidot < 0) the share of the absorbed mechanical
/// power returned, (V I) / (tau phidot); otherwise (braking without regeneration, or power
/// lost both ways) 0.
double efficiency(const MotorParams& m, const DriverParams& d, double voltage_V, double phidot_rad_s);

/// Steady no-load speed at voltage V (tau = 0, phidot > 0), rad/s. Closed form.
double no_load_speed(const MotorParams& m, double voltage_V);

/// Stall torque at voltage V (phidot = 0), N m: K_T (V/Omega - I_0 sgn_s(0)) = K_T V / Omega.
double stall_torque(const MotorParams& m, double voltage_V);

/// Voltage an active motor needs to give torque tau at speed phidot, V (ignores clamping).
double voltage_for_torque(const MotorParams& m, double torque_Nm, double phidot_rad_s);

}  // namespace maptr::model
