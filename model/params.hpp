#pragma once
// Parameters of the MAPTR model (paper Table 1, with the values the paper does not give
// chosen and documented in docs/MODEL.md "Deviations from the paper").
#include <stdexcept>
#include <string>

namespace maptr::model {

/// Thrown for a motor type the paper has no data for; the message names the field and the value.
/// The ranges of the parameters a scenario sets are checked by its field table
/// (config/scenario_fields.cpp), not here.
class ParamError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Permanent-magnet DC motor, gearless (wheel on the shaft). SI units.
struct MotorParams {
  std::string type = "I";               ///< "I" or "II" (paper Table 1)
  double rated_voltage_V = 24.0;        ///< V
  double no_load_current_A = 0.050;     ///< I_0, A
  double no_load_speed_rpm = 5930.0;    ///< datasheet, rpm (used only for checks)
  double stall_torque_Nm = 0.130;       ///< datasheet, N m (used only for checks)
  double resistance_ohm = 7.03;         ///< Omega, armature resistance
  double viscous_Nms = 6e-7;            ///< b_damp, N m s/rad
  double torque_constant_NmA = 38.2e-3; ///< K_T, N m/A
  double back_emf_Vs = 38.4e-3;         ///< K_e, V s/rad
  double mass_kg = 0.21;                ///< motor mass, kg
  double friction_sign_scale_rad_s = 0.5;  ///< smooth sign tanh(phidot/scale) for K_T I_0, rad/s

};

/// A parameter value as error messages print it.
std::string param_value(double v);

/// Motor of Table 1 by name: "I" or "II" ("III" has no data in the paper). Throws ParamError.
MotorParams motor_type(const std::string& name);

/// Two-term exponential battery V_B(d) = h e^{w d} + y e^{z d}, d = discharge in mAh.
struct BatteryParams {
  double h = -1.851e-14;
  double w = 0.005345;     ///< 1/mAh
  double y = 23.4;         ///< V
  double z = -1.018e-5;    ///< 1/mAh
  double capacity_mAh = 6395.0;
};

/// The motor driver of every agent (docs/MODEL.md "Driver").
///   unidirectional: a low-side switch, V in [0, V_B], I_a >= 0 (no braking: the paper's)
///   bidirectional:  an H-bridge, V in [-V_B, V_B], I_a of either sign. Power that flows back
///                   (V I_a < 0, braking) is dissipated in the driver, or with regeneration
///                   returned to the battery up to charge_limit_A per side; the rest dissipated.
struct DriverParams {
  bool bidirectional = false;
  bool regeneration = false;     ///< bidirectional only: braking power charges the battery
  double charge_limit_A = 5.0;   ///< most charging current one side's battery takes, A
  /// Lowest voltage the driver applies at battery voltage V_B: -V_B (H-bridge) or 0.
  double floor_V(double battery_V) const { return bidirectional ? -battery_V : 0.0; }
  const char* name() const { return bidirectional ? "bidirectional" : "unidirectional"; }
};

/// The whole robot. N agents, N/2 per side, N/4 rows of 4 wheels spaced b apart, centred.
struct RobotParams {
  int agents = 16;                 ///< N, multiple of 4, 4..512
  double gross_mass_kg = 13.2;     ///< m: payload + chassis + motors + wheels, kg
  double track_m = 0.2;            ///< a, distance between left and right wheel columns, m
  double row_spacing_m = 0.08;     ///< b, distance between wheel rows, m
  double wheel_radius_m = 0.035;   ///< r, m
  double wheel_mass_kg = 0.05;     ///< m_w, kg
  double mu_rolling = 0.01;        ///< mu_s
  double mu_lateral = 0.1;         ///< mu_l
  double k_s = 100.0;              ///< friction smoothing constant, s/m (not in the paper)
  double gravity = 9.81;           ///< m/s^2
  /// I_zz in kg m^2; <= 0 means derived: plate of (N/4) b x a carrying the gross mass,
  /// m ((N/4 b)^2 + a^2) / 12.
  double yaw_inertia_kgm2 = 0.0;
  /// Wheel inertia in kg m^2; <= 0 means derived: disc m_w r^2 / 2.
  double wheel_inertia_kgm2 = 0.0;
  MotorParams motor;
  DriverParams driver;
  BatteryParams battery;

  int per_side() const { return agents / 2; }
  int rows() const { return agents / 4; }
  double yaw_inertia() const;    ///< effective I_zz, kg m^2
  double wheel_inertia() const;  ///< effective I_w, kg m^2
  /// Longitudinal offset of wheel row j (0 = rearmost), m: (j - (rows-1)/2) b.
  double row_offset(int j) const;
};

}  // namespace maptr::model
