#pragma once
// Fault detection of one side's agents (docs/ARCHITECTURE.md "Fault detection"). The group checks
// each agent against the physics instead of trusting it, from what the plant measured of its
// drive at t_k (msg::SideTick) and the healthy motor model (model/motor.hpp):
//   A  measured current:  r_A = I_measured(t_k) - I_model(V_{k-1}, phidot_k)
//      (V_{k-1}: the voltage the agent said it applied over [t_{k-1}, t_k]; 0 A when idle)
//   B  reported current:  r_B = I_reported(t_{k-1}) - I_model(V_{k-1}, phidot_{k-1})
//      (an agent reports the current its own voltage gives at the speed it read)
//   C  erratic voltage:   c_k = (V_k - V_{k-1}) - median over the side's driving agents of the same,
//      j_k = |c_k - c_{k-1}|; healthy agents share one speed error, so their PIDs step together
//      (a steady c, as a wrong sensor winds the integrator up, is not jitter)
// |r_A| or |r_B| above fault_current_A on every tick of the persistence time, or the median of j
// over it above fault_jitter_V, flags the agent with the fault it looks like:
//   A: no current at all -> open; the winding sees 0 V (V_eff = I R + K_e phidot = 0) -> short;
//      more current than the model, as a weak magnet's smaller back-EMF gives (the factor
//      F = (V - I R) / (K_e phidot) in (0, 1)) -> torque; less, as a larger resistance gives
//      (F = (V - K_e phidot) / (I R) > 1) -> resistance; neither, with V_eff steady and not the
//      agent's voltage -> stuck
//   B: the speed the report implies, (V - I R) / K_e, is the measured one plus a steady offset ->
//      sensor; otherwise -> liar
//   C: erratic
// A flagged agent is isolated (the group neither counts nor assigns it, the plant disconnects it)
// until fault_probation_s has passed; flagged again, its probation doubles.
// Pure: explicit time, no DDS, no clock.
#include <cstdint>
#include <deque>
#include <vector>

#include "control/tunable.hpp"
#include "model/params.hpp"

namespace maptr::control {

enum class Diagnosis : uint8_t { kNone = 0, kOpen, kShort, kTorque, kResistance, kStuck, kSensor, kErratic, kLiar };
constexpr int kDiagnosisCount = 9;
/// "open", "short", "torque", "resistance", "stuck", "sensor", "erratic", "liar" ("" for none).
const char* diagnosis_name(Diagnosis d);

/// The detection's thresholds: the scenario's control.fault_* fields, declared here and nowhere
/// else (config/scenario_fields.cpp gives each its range and description).
struct DiagnosisTuning {
  double fault_current_A = 0.01;     ///< residual threshold of channels A and B, A
  double fault_jitter_V = 0.5;       ///< threshold of channel C (median |c|), V
  double fault_persistence_s = 0.1;  ///< s a residual must last
  double fault_probation_s = 10.0;   ///< s an isolated agent stays out (doubled at each relapse)
};

/// The rows of DiagnosisTuning's fields in the scenario (control/tunable.hpp).
inline std::vector<Tunable<DiagnosisTuning>> diagnosis_tunables() {
  using T = DiagnosisTuning;
  const auto above = Bounds::above;
  return {
      real_tunable<T>(
          "control.fault_current_A", [](T& t) -> double& { return t.fault_current_A; }, above(0, 1e3), "A",
          "a measured current off the motor model's, or a reported one off the measured speed's, by more "
          "than this is a residual"),
      real_tunable<T>(
          "control.fault_jitter_V", [](T& t) -> double& { return t.fault_jitter_V; }, above(0, 1e3), "V",
          "an agent's voltage steps apart from its side's median step, their median over the persistence "
          "time beyond this is a residual (erratic voltages)"),
      real_tunable<T>(
          "control.fault_persistence_s", [](T& t) -> double& { return t.fault_persistence_s; }, above(0, 1e3),
          "s", "a residual that lasts this long flags the agent faulty"),
      real_tunable<T>(
          "control.fault_probation_s", [](T& t) -> double& { return t.fault_probation_s; }, above(0, 1e7),
          "s", "an isolated agent is let back after this long, doubled each time it is flagged again"),
  };
}

/// The thresholds and what the group knows of its robot.
struct DiagnosisConfig : DiagnosisTuning {
  model::MotorParams motor;
  model::DriverParams driver;
  double dt_s = 0.01;
};

/// What the plant measured of one agent's drive at t_k.
struct DriveSample {
  bool drove = false;         ///< it replied driving over [t_{k-1}, t_k]
  double drive_V = 0.0;       ///< the voltage it applied over [t_{k-1}, t_k], V
  double measured_A = 0.0;    ///< current in its motor's lead at t_k, A
  bool reported = false;      ///< it replied at tick k-1
  double reported_A = 0.0;    ///< the current it reported then, A
};

/// One side at t_k.
struct SideSample {
  double phidot = 0.0;       ///< rad/s, the side's wheel speed at t_k (encoders)
  double phidot_prev = 0.0;  ///< rad/s, at t_{k-1}
  std::vector<DriveSample> agents;
};

/// A change of an agent's flag (for logs and tests).
struct DiagnosisChange {
  int index = 0;
  Diagnosis flag = Diagnosis::kNone;  ///< kNone: let back after probation
};

class SideDiagnosis {
 public:
  SideDiagnosis(int per_side, const DiagnosisConfig& c);
  /// Checks tick k (time t); returns the flags' changes. flags() then holds the flags in force.
  std::vector<DiagnosisChange> step(double t, const SideSample& s);
  /// 0: healthy, else the Diagnosis, per agent.
  const std::vector<uint8_t>& flags() const { return flags_; }
  int persistence_ticks() const { return need_; }

 private:
  struct Sample {
    bool drove;
    double drive_V, measured_A, expected_A, reported_A, phidot, phidot_prev;
  };
  struct Agent {
    std::deque<Sample> a, b;        ///< consecutive samples beyond the threshold, channels A and B
    std::deque<double> jitter;      ///< channel C, the last ticks' |c_k - c_{k-1}| (consecutive driving ticks)
    double last_c = 0.0;
    bool has_c = false;
    double last_V = 0.0;
    bool last_drove = false;
    double isolated_t = 0.0;
    double probation_s = 0.0;
    int flagged = 0;  ///< times flagged so far
  };
  Diagnosis classify_a(const std::deque<Sample>& w) const;
  Diagnosis classify_b(const std::deque<Sample>& w) const;
  void reset(Agent& a);
  /// Channel C: the agent's voltage step apart from the side's median step.
  void watch_jitter(Agent& a, const DriveSample& d, double median, bool side_steps);
  /// The flag its residuals call for (kNone: none yet).
  Diagnosis verdict(const Agent& a) const;

  DiagnosisConfig c_;
  int need_;
  std::vector<Agent> agents_;
  std::vector<uint8_t> flags_;
};

}  // namespace maptr::control
