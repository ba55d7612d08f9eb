#pragma once
// Faults of one agent's motor and driver, as the plant integrates them (docs/MODEL.md "Motor
// faults"). Closed forms, with the healthy motor of model/motor.hpp (K_T, K_e, Omega, I_0, b):
//   open            the winding carries no current:           I = 0,  tau = -b phidot
//   short           the driver's output is shorted (a failed bridge): the winding sees 0 V
//                   whatever the agent asks, while the driver is connected:
//                                  I = -K_e phidot / Omega,  tau = K_T (I - I_0 sgn_s) - b phidot
//                   (a braking torque proportional to speed; I^2 Omega heats the winding, the
//                   battery gives nothing)
//   torque=F        a weakened magnet: K_T and K_e times F (the friction torque K_T I_0 kept)
//   resistance=F    the winding's resistance Omega times F
//   stuck=V         the driver applies V volts (clamped to its range) whatever it is told
// A motor its group disconnected (its driver's supply opened) is an open circuit whatever its
// fault. Faults of the agent's software (a wrong speed sensor, erratic or lying replies) are
// not here: the agent misbehaves with them (agent/misbehaviour.hpp).
#include <cstdint>
#include <string>

#include "model/params.hpp"

namespace maptr::model {

enum class MotorFaultKind : uint8_t { kNone = 0, kOpen, kShort, kTorque, kResistance, kStuck };

struct MotorFault {
  MotorFaultKind kind = MotorFaultKind::kNone;
  double value = 0.0;  ///< torque, resistance: the factor F; stuck: the voltage, V
  bool healthy() const { return kind == MotorFaultKind::kNone; }
};

/// The motor's parameters under a fault: torque=F scales K_T and K_e by F (and I_0 by 1/F, so
/// that the friction torque K_T I_0 stays), resistance=F scales Omega by F; others unchanged.
MotorParams faulted_params(const MotorParams& m, const MotorFault& f);

/// What one motor's winding is driven with over a tick.
struct Winding {
  bool conducts = false;  ///< driven at voltage_V (else an open circuit)
  double voltage_V = 0.0;
  bool shorted = false;   ///< the short: conducts at 0 V, current of either sign, no battery draw
};

/// The winding of a motor whose agent asked to drive (`driven`) at asked_V, given its fault and
/// whether its group disconnected it; a stuck driver's voltage is clamped to [lo_V, hi_V].
Winding winding(const MotorFault& f, bool driven, double asked_V, bool disconnected, double lo_V, double hi_V);

/// Armature current of a motor with this winding and fault at speed phidot, A: what a current
/// sensor in the motor's lead measures (0 for an open circuit).
double winding_current(const MotorParams& m, const DriverParams& d, const MotorFault& f, const Winding& w,
                       double phidot_rad_s);

/// Name of a fault kind as scenarios write it ("open", "short", "torque", "resistance",
/// "stuck"; "" for none), and back (false for an unknown name).
const char* motor_fault_name(MotorFaultKind k);
bool parse_motor_fault(const std::string& name, MotorFaultKind& k);

}  // namespace maptr::model
