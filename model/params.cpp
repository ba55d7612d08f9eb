#include "model/params.hpp"

#include <cmath>
#include <sstream>

namespace maptr::model {
std::string param_value(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
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

}  // namespace maptr::model
