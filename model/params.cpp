#include "model/params.hpp"

#include <cmath>
#include <sstream>

namespace maptr::model {
std::string param_value(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

namespace {

void require(bool ok, const std::string& field, const std::string& value, const std::string& why) {
  if (!ok) throw ParamError(field + " = " + value + ": " + why);
}

void positive(double v, const std::string& field) {
  require(std::isfinite(v) && v > 0.0, field, param_value(v), "must be a positive finite number");
}

void non_negative(double v, const std::string& field) {
  require(std::isfinite(v) && v >= 0.0, field, param_value(v), "must be a non-negative finite number");
}

}  // namespace

void MotorParams::validate() const {
  require(type == "I" || type == "II", "motor.type", type, "unknown motor type (known: I, II)");
  positive(rated_voltage_V, "motor.rated_voltage_V");
  non_negative(no_load_current_A, "motor.no_load_current_A");
  positive(resistance_ohm, "motor.resistance_ohm");
  non_negative(viscous_Nms, "motor.viscous_Nms");
  positive(torque_constant_NmA, "motor.torque_constant_NmA");
  positive(back_emf_Vs, "motor.back_emf_Vs");
  positive(friction_sign_scale_rad_s, "motor.friction_sign_scale_rad_s");
}

MotorParams motor_type(const std::string& name) {
  MotorParams m;
  if (name == "I") return m;
  if (name == "II") {
    m.type = "II";
    m.rated_voltage_V = 6.0;
    m.no_load_current_A = 0.250;
    m.no_load_speed_rpm = 5500.0;
    m.stall_torque_Nm = 17.6e-3;
    m.resistance_ohm = 2.4;
    m.viscous_Nms = 2.2e-7;
    m.torque_constant_NmA = 7e-3;
    m.back_emf_Vs = 7e-3;
    m.mass_kg = 0.11;
    return m;
  }
  if (name == "III")
    throw ParamError("motor.type = III: the paper gives no data for Type III (known: I, II)");
  throw ParamError("motor.type = " + name + ": unknown motor type (known: I, II)");
}

void BatteryParams::validate() const {
  require(std::isfinite(h), "battery.h", param_value(h), "must be finite");
  require(std::isfinite(w), "battery.w", param_value(w), "must be finite");
  require(std::isfinite(z), "battery.z", param_value(z), "must be finite");
  positive(y, "battery.y");
  positive(capacity_mAh, "battery.capacity_mAh");
}

void RobotParams::validate() const {
  require(agents >= 4 && agents <= 512 && agents % 4 == 0, "agents", std::to_string(agents),
          "must be a multiple of 4 between 4 and 512");
  positive(gross_mass_kg, "gross_mass_kg");
  positive(track_m, "track_m");
  positive(row_spacing_m, "row_spacing_m");
  positive(wheel_radius_m, "wheel_radius_m");
  non_negative(wheel_mass_kg, "wheel_mass_kg");
  non_negative(mu_rolling, "mu_rolling");
  non_negative(mu_lateral, "mu_lateral");
  positive(k_s, "k_s");
  positive(gravity, "gravity");
  require(std::isfinite(yaw_inertia_kgm2), "yaw_inertia_kgm2", param_value(yaw_inertia_kgm2), "must be finite");
  require(std::isfinite(wheel_inertia_kgm2), "wheel_inertia_kgm2", param_value(wheel_inertia_kgm2),
          "must be finite");
  motor.validate();
  driver.validate();
  battery.validate();
}

void DriverParams::validate() const {
  positive(charge_limit_A, "driver.charge_limit_A");
  require(bidirectional || !regeneration, "driver.regeneration", "true",
          "only a bidirectional driver can regenerate");
}

double RobotParams::yaw_inertia() const {
  if (yaw_inertia_kgm2 > 0.0) return yaw_inertia_kgm2;
  const double length = rows() * row_spacing_m;
  return gross_mass_kg * (length * length + track_m * track_m) / 12.0;
}

double RobotParams::wheel_inertia() const {
  if (wheel_inertia_kgm2 > 0.0) return wheel_inertia_kgm2;
  return 0.5 * wheel_mass_kg * wheel_radius_m * wheel_radius_m;
}

double RobotParams::row_offset(int j) const {
  return (j - 0.5 * (rows() - 1)) * row_spacing_m;
}

void PidParams::validate() const {
  non_negative(kp, "pid.kp");
  non_negative(ki, "pid.ki");
  non_negative(kd, "pid.kd");
  require(kp + ki > 0.0, "pid.kp", param_value(kp), "kp and ki cannot both be zero");
}

}  // namespace maptr::model
