#pragma once
// Level-1 wheel-speed PID (paper eq. PID with the error sign corrected):
//   e = phidot_ref - phidot,  V = K_P e + K_I E + K_D de/dt,  E = integral of e dt,
// clamped to [V_min, V_max] (V_max = battery voltage; V_min = 0, or -V_B with an H-bridge). Anti-windup by conditional integration:
// the integral is not advanced when the output is saturated and the error pushes further
// into saturation. Explicit time: the caller passes dt; no clock is read.
namespace maptr::control {

/// Level-1 PID gains (the scenario's control.kp, control.ki, control.kd). Output is a motor
/// voltage, V.
struct PidGains {
  double kp = 0.5;  ///< V per rad/s
  double ki = 2.0;  ///< V per rad
  double kd = 0.0;  ///< V s^2/rad (acts on the error rate, rad/s^2)
};

class Pid {
 public:
  explicit Pid(PidGains g = {}) : g_(g) {}

  /// One control step; returns the voltage clamped to [v_min_V, max(v_min_V, v_max_V)], V.
  double update(double error_rad_s, double dt_s, double v_min_V, double v_max_V);
  /// The same clamped to [0, v_max_V] (a unidirectional driver).
  double update(double error_rad_s, double dt_s, double v_max_V) { return update(error_rad_s, dt_s, 0.0, v_max_V); }
  void reset();
  /// Bumpless start: set the integral so that a zero error gives output_V.
  void preload(double output_V);
  /// Join running controllers: take the state of a PID whose last step, at error e_prev, gave
  /// output_V (integral (output_V - K_P e_prev) / K_I, previous error e_prev). Fed the same errors
  /// from then on, this PID and that one give the same outputs (exactly for K_D = 0 and while
  /// neither saturates).
  void align(double output_V, double prev_error_rad_s);
  double integral() const { return integral_; }
  bool saturated() const { return saturated_; }

 private:
  PidGains g_;
  double integral_ = 0.0;    ///< rad
  double prev_error_ = 0.0;  ///< rad/s
  bool first_ = true;
  bool saturated_ = false;
};

}  // namespace maptr::control
