#include "control/level1/pid.hpp"

#include <algorithm>

namespace maptr::control {

double Pid::update(double e, double dt, double v_min, double v_max) {
  if (!(dt > 0.0)) return 0.0;  // no time passed: no valid control step (never NaN)
  const double de = first_ ? 0.0 : (e - prev_error_) / dt;
  first_ = false;
  prev_error_ = e;
  const double candidate_i = integral_ + e * dt;
  const double unclamped = g_.kp * e + g_.ki * candidate_i + g_.kd * de;
  const double out = std::clamp(unclamped, v_min, std::max(v_min, v_max));
  const bool high = unclamped > out, low = unclamped < out;
  saturated_ = high || low;
  // Conditional integration: keep the new integral unless it deepens the saturation.
  if (!((high && e > 0.0) || (low && e < 0.0))) integral_ = candidate_i;
  return out;
}

void Pid::reset() {
  integral_ = 0.0;
  prev_error_ = 0.0;
  first_ = true;
  saturated_ = false;
}

void Pid::align(double out, double prev_error) {
  reset();
  if (g_.ki > 0.0) integral_ = (out - g_.kp * prev_error) / g_.ki;
  prev_error_ = prev_error;
  first_ = false;
}

void Pid::preload(double out) {
  reset();
  if (g_.ki > 0.0) integral_ = out / g_.ki;
}

}  // namespace maptr::control
