// Level-1 PID (control/level1/pid.hpp): e = phidot_ref - phidot, V = K_P e + K_I E + K_D de/dt, clamped to
// [0, V_max].
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "control/level1/pid.hpp"
#include "model/params.hpp"

namespace {

using maptr::control::Pid;
using maptr::control::PidGains;

PidGains gains(double kp, double ki, double kd) {
  PidGains g;
  g.kp = kp;
  g.ki = ki;
  g.kd = kd;
  return g;
}

TEST(Pid, ProportionalOnly) {
  Pid pid(gains(0.5, 0.0, 0.0));
  // V = K_P e: 0.5 * 10 = 5 V, 0.5 * 30 = 15 V (exact in binary).
  EXPECT_DOUBLE_EQ(pid.update(10.0, 0.01, 24.0), 5.0);
  EXPECT_DOUBLE_EQ(pid.update(30.0, 0.01, 24.0), 15.0);
  // The error sign: a wheel slower than its reference (e > 0) gets a positive voltage.
  EXPECT_GT(pid.update(1.0, 0.01, 24.0), 0.0);
}

TEST(Pid, ClampsToZeroAndVmax) {
  Pid pid(gains(0.5, 0.0, 0.0));
  EXPECT_DOUBLE_EQ(pid.update(100.0, 0.01, 24.0), 24.0);  // 50 V wanted
  EXPECT_TRUE(pid.saturated());
  EXPECT_DOUBLE_EQ(pid.update(100.0, 0.01, 9.0), 9.0);   // V_max follows the battery voltage
  EXPECT_DOUBLE_EQ(pid.update(-10.0, 0.01, 24.0), 0.0);  // no reversing: never below 0
  EXPECT_TRUE(pid.saturated());
  EXPECT_DOUBLE_EQ(pid.update(10.0, 0.01, 24.0), 5.0);
  EXPECT_FALSE(pid.saturated());
  EXPECT_DOUBLE_EQ(pid.update(10.0, 0.01, -3.0), 0.0);  // a nonsensical V_max < 0 gives 0
}

TEST(Pid, IntegralIsTheSumOfErrorTimesExplicitDt) {
  // E = sum e_k dt_k with the caller's dt (no clock): 2*0.01 + 3*0.02 + (-1)*0.005 + 4*0.1 = 0.475 rad.
  Pid pid(gains(0.0, 2.0, 0.0));
  const std::vector<double> e = {2.0, 3.0, -1.0, 4.0}, dt = {0.01, 0.02, 0.005, 0.1};
  double out = 0.0;
  for (std::size_t k = 0; k < e.size(); ++k) out = pid.update(e[k], dt[k], 24.0);
  EXPECT_NEAR(pid.integral(), 0.475, 1e-15);
  EXPECT_NEAR(out, 2.0 * 0.475, 1e-15);
  // Same sequence, same outputs: the controller depends on its arguments only.
  Pid twin(gains(0.0, 2.0, 0.0));
  double out2 = 0.0;
  for (std::size_t k = 0; k < e.size(); ++k) out2 = twin.update(e[k], dt[k], 24.0);
  EXPECT_EQ(out, out2);
}

TEST(Pid, DerivativeUsesExplicitDtAndNoFirstStepKick) {
  Pid pid(gains(0.0, 0.0, 0.1));
  // First step: no previous error, no derivative kick.
  EXPECT_DOUBLE_EQ(pid.update(5.0, 0.01, 24.0), 0.0);
  // Second: K_D (e2 - e1) / dt = 0.1 * (8 - 5) / 0.02 = 15 V.
  EXPECT_NEAR(pid.update(8.0, 0.02, 24.0), 15.0, 1e-12);
  // After reset the kick is suppressed again.
  pid.reset();
  EXPECT_DOUBLE_EQ(pid.update(100.0, 0.01, 24.0), 0.0);
}

TEST(Pid, AntiWindupHoldsTheIntegralWhileSaturated) {
  Pid pid(gains(0.5, 2.0, 0.0));
  // e = 100 rad/s wants 50 V + integral: saturated high with e > 0, integral held at 0.
  for (int k = 0; k < 500; ++k) {
    EXPECT_DOUBLE_EQ(pid.update(100.0, 0.01, 24.0), 24.0);
    EXPECT_EQ(pid.integral(), 0.0);
  }
  // When the error drops the output leaves saturation at once: 0.5 * 10 + 2 * (10 * 0.01) = 5.2 V
  // (without anti-windup the integral would be 5 rad and the output still clamped at 24 V).
  EXPECT_NEAR(pid.update(10.0, 0.01, 24.0), 5.2, 1e-14);
  EXPECT_NEAR(pid.integral(), 0.1, 1e-15);
  // Saturated low with e < 0: the integral does not decrease either.
  for (int k = 0; k < 100; ++k) EXPECT_DOUBLE_EQ(pid.update(-50.0, 0.01, 24.0), 0.0);
  EXPECT_NEAR(pid.integral(), 0.1, 1e-15);
}

TEST(Pid, AntiWindupLetsTheIntegralUnwind) {
  // Saturated high but the error pulls back (e < 0): integrating is allowed.
  Pid pid(gains(0.5, 2.0, 0.0));
  pid.preload(30.0);  // integral 15 rad, output 30 V > V_max = 24 V
  EXPECT_DOUBLE_EQ(pid.update(-1.0, 0.01, 24.0), 24.0);
  EXPECT_TRUE(pid.saturated());
  EXPECT_NEAR(pid.integral(), 15.0 - 0.01, 1e-14);
}

TEST(Pid, PreloadGivesTheRequestedOutputAtZeroError) {
  for (double target : {0.0, 3.3, 12.0, 23.9}) {
    Pid pid(gains(0.5, 2.0, 0.0));
    pid.preload(target);
    // integral = target / K_I, so K_I E = target; 1e-14 V.
    EXPECT_NEAR(pid.update(0.0, 0.01, 24.0), target, 1e-14) << target;
  }
  // Preload is also clamped on output like any other step.
  Pid pid(gains(0.5, 2.0, 0.0));
  pid.preload(30.0);
  EXPECT_DOUBLE_EQ(pid.update(0.0, 0.01, 24.0), 24.0);
}

TEST(Pid, AlignGivesTheSameOutputsAsTheRunningController) {
  PidGains g;
  Pid running(g), joining(g);
  double e_prev = 0.0, v = 0.0;
  for (int k = 0; k < 50; ++k) {
    e_prev = 10.0 * std::cos(0.1 * k);
    v = running.update(e_prev, 0.01, 1e9);
  }
  joining.align(v, e_prev);
  for (int k = 50; k < 200; ++k) {
    const double e = 10.0 * std::cos(0.1 * k);
    EXPECT_NEAR(running.update(e, 0.01, 1e9), joining.update(e, 0.01, 1e9), 1e-12) << k;
  }
}

}  // namespace
