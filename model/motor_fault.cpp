#include "model/motor_fault.hpp"

#include <algorithm>

#include "model/motor.hpp"

namespace maptr::model {

MotorParams faulted_params(const MotorParams& m, const MotorFault& f) {
  MotorParams p = m;
  if (f.kind == MotorFaultKind::kTorque) {
    p.torque_constant_NmA *= f.value;
    p.back_emf_Vs *= f.value;
    p.no_load_current_A /= f.value;
  } else if (f.kind == MotorFaultKind::kResistance) {
    p.resistance_ohm *= f.value;
  }
  return p;
}

Winding winding(const MotorFault& f, bool driven, double asked_V, bool disconnected, double lo_V, double hi_V) {
  if (disconnected || f.kind == MotorFaultKind::kOpen) return {};
  if (f.kind == MotorFaultKind::kShort) return {true, 0.0, true};
  if (f.kind == MotorFaultKind::kStuck) return {true, std::clamp(f.value, lo_V, hi_V), false};
  return {driven, driven ? asked_V : 0.0, false};
}

double winding_current(const MotorParams& m, const DriverParams& d, const MotorFault& f, const Winding& w,
                       double phidot) {
  if (!w.conducts) return 0.0;
  const MotorParams p = faulted_params(m, f);
  if (w.shorted) return -p.back_emf_Vs * phidot / p.resistance_ohm;
  return armature_current(p, d, w.voltage_V, phidot);
}

namespace {
constexpr const char* kNames[] = {"", "open", "short", "torque", "resistance", "stuck"};
}

const char* motor_fault_name(MotorFaultKind k) { return kNames[static_cast<int>(k)]; }

bool parse_motor_fault(const std::string& name, MotorFaultKind& k) {
  for (int i = 1; i < 6; ++i)
    if (name == kNames[i]) {
      k = static_cast<MotorFaultKind>(i);
      return true;
    }
  return false;
}

}  // namespace maptr::model
