// DC motor model (model/motor.hpp) against Table 1 and closed forms.
#include <gtest/gtest.h>

#include "tests/unit/test_support.hpp"

#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>
#include <string>

#include "model/motor.hpp"

namespace {

using maptr::test::record;
using maptr::test::bisect;

using maptr::model::MotorParams;
namespace mm = maptr::model;

constexpr double kRpmPerRadS = 60.0 / (2.0 * M_PI);

// Speed at which the net torque of an active motor at voltage v vanishes, by bisection on
// active_torque(armature_current(v, w), w) = 0 over (1 rad/s, v / K_e] (at v / K_e the current is 0
// and the torque is -K_T I_0 - b w < 0).
double no_load_speed_by_bisection(const MotorParams& m, double v) {
  auto f = [&](double w) { return mm::active_torque(m, mm::armature_current(m, {}, v, w), w); };
  return bisect(f, 1.0, v / m.back_emf_Vs, 1e-12);
}

TEST(Motor, TypeINoLoadSpeedAndStallTorque) {
  const MotorParams m = mm::motor_type("I");
  const double w0 = mm::no_load_speed(m, 24.0);
  // Table 1's constants give (K_T V/R - K_T I_0) / (b + K_T K_e / R) = 614.08 rad/s = 5864 rpm,
  // 1.1 % below the 5930 rpm datasheet value: tolerance 2 %.
  const double rpm = w0 * kRpmPerRadS;
  EXPECT_NEAR(rpm, 5930.0, 0.02 * 5930.0);
  EXPECT_NEAR(rpm, 5864.0, 0.5);  // hand evaluation of the closed form above
  record("typeI_no_load_rel_err_vs_datasheet", (rpm - 5930.0) / 5930.0);
  // The closed form assumes the smooth friction sign is 1 at speed (tanh(614 / 0.5) = 1 in double):
  // it must agree with a numerical root of the model's own torque to 1e-6 rad/s.
  const double w_bis = no_load_speed_by_bisection(m, 24.0);
  EXPECT_NEAR(w0, w_bis, 1e-6);
  record("typeI_no_load_closed_vs_bisection_rad_s", std::fabs(w0 - w_bis));

  // Stall torque K_T V / R = 0.0382 * 24 / 7.03 = 0.13041 N m, datasheet 0.130 N m: tolerance 1 %.
  const double ts = mm::stall_torque(m, 24.0);
  EXPECT_NEAR(ts, 0.130, 0.01 * 0.130);
  EXPECT_NEAR(ts, 0.0382 * 24.0 / 7.03, 1e-15);
  record("typeI_stall_rel_err_vs_datasheet", (ts - 0.130) / 0.130);
  // At standstill the model's torque is exactly K_T V / R (smooth sign of 0 is 0): 1e-15.
  EXPECT_NEAR(mm::active_torque(m, mm::armature_current(m, {}, 24.0, 0.0), 0.0), ts, 1e-15);
}

TEST(Motor, TypeIINoLoadSpeedAndStallTorque) {
  const MotorParams m = mm::motor_type("II");
  const double w0 = mm::no_load_speed(m, 6.0);
  // Table 1's Type II constants are not consistent with its 5500 rpm: even the ideal motor
  // (I_0 = b = 0) would run at V / K_e = 6 / 0.007 = 857 rad/s = 8185 rpm. With I_0 and b the
  // closed form gives (0.0175 - 0.00175) / (2.2e-7 + 4.9e-5 / 2.4) = 763.2 rad/s = 7288 rpm, 32.5 %
  // above the datasheet. The honest tolerance against the datasheet is therefore 33 %; the model is
  // also pinned to the hand value 7288 rpm (0.5 rpm) so that a drift is noticed.
  const double rpm = w0 * kRpmPerRadS;
  EXPECT_NEAR(rpm, 5500.0, 0.33 * 5500.0);
  EXPECT_NEAR(rpm, 7288.0, 0.5);
  record("typeII_no_load_rel_err_vs_datasheet", (rpm - 5500.0) / 5500.0);
  const double w_bis = no_load_speed_by_bisection(m, 6.0);
  EXPECT_NEAR(w0, w_bis, 1e-6);
  record("typeII_no_load_closed_vs_bisection_rad_s", std::fabs(w0 - w_bis));

  // Stall torque K_T V / R = 0.007 * 6 / 2.4 = 0.0175 N m vs 0.0176 datasheet (-0.57 %): tolerance 1 %.
  const double ts = mm::stall_torque(m, 6.0);
  EXPECT_NEAR(ts, 17.6e-3, 0.01 * 17.6e-3);
  EXPECT_NEAR(ts, 0.0175, 1e-15);
  record("typeII_stall_rel_err_vs_datasheet", (ts - 17.6e-3) / 17.6e-3);
}

// Sweeps the speed from stall to no load at voltage v and returns the torque fraction
// (of stall torque) where the efficiency peaks; checks 0 <= eta <= 1 everywhere.
double efficiency_peak_fraction(const MotorParams& m, double v, double* eta_max) {
  const double w0 = mm::no_load_speed(m, v);
  const double ts = mm::stall_torque(m, v);
  const int n = 20000;
  double best = -1.0, best_w = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double w = w0 * k / n;
    const double eta = mm::efficiency(m, {}, v, w);
    EXPECT_GE(eta, 0.0) << "w = " << w;
    EXPECT_LE(eta, 1.0) << "w = " << w;
    if (eta > best) {
      best = eta;
      best_w = w;
    }
  }
  *eta_max = best;
  return mm::active_torque(m, mm::armature_current(m, {}, v, best_w), best_w) / ts;
}

TEST(Motor, EfficiencyBoundsZerosAndPeakLocation) {
  for (const char* type : {"I", "II"}) {
    const MotorParams m = mm::motor_type(type);
    for (double frac : {1.0, 0.5, 0.25}) {
      const double v = frac * m.rated_voltage_V;
      // Zero at stall (no output power) and at no load (no output torque); 1e-9 absolute.
      EXPECT_NEAR(mm::efficiency(m, {}, v, 0.0), 0.0, 1e-12);
      EXPECT_NEAR(mm::efficiency(m, {}, v, mm::no_load_speed(m, v)), 0.0, 1e-9);
      // Beyond no load the motor brakes: efficiency reported as 0.
      EXPECT_EQ(mm::efficiency(m, {}, v, 1.05 * mm::no_load_speed(m, v)), 0.0);
      double eta_max = 0.0;
      const double peak = efficiency_peak_fraction(m, v, &eta_max);
      // Paper: maximum efficiency around 10-20 % of stall torque; asserted range 5-30 %.
      EXPECT_GT(peak, 0.05) << type << " at " << v << " V";
      EXPECT_LT(peak, 0.30) << type << " at " << v << " V";
      // Independent closed form, parametrised by the current instead of the speed (tanh = 1 at speed):
      //   w(I) = (V - I R) / K_e,  eta(I) = (K_T (I - I_0) w - b w^2) / (V I),
      // maximised over I in [I_0, V/R] by golden section. Peak efficiency within 1e-6, its torque
      // fraction within 2e-4 (the sweep has 20000 speed steps).
      const double kt = m.torque_constant_NmA, ke = m.back_emf_Vs, res = m.resistance_ohm;
      const double i0 = m.no_load_current_A, bv = m.viscous_Nms;
      auto eta_of_i = [&](double i) {
        const double w = (v - i * res) / ke;
        return (kt * (i - i0) * w - bv * w * w) / (v * i);
      };
      double lo = i0, hi = v / res;
      const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
      for (int it = 0; it < 200; ++it) {
        const double c1 = hi - phi * (hi - lo), c2 = lo + phi * (hi - lo);
        if (eta_of_i(c1) > eta_of_i(c2)) hi = c2; else lo = c1;
      }
      const double i_star = 0.5 * (lo + hi);
      const double w_star = (v - i_star * res) / ke;
      const double eta_cf = eta_of_i(i_star);
      const double peak_cf = (kt * (i_star - i0) - bv * w_star) / (kt * v / res);
      EXPECT_NEAR(eta_max, eta_cf, 1e-6) << type << " at " << v << " V";
      EXPECT_NEAR(peak, peak_cf, 2e-4) << type << " at " << v << " V";
      // Classical estimate (b = 0, K_e = K_T): I* = sqrt(I_stall I_0), torque fraction
      // sqrt(I_0 / I_stall) - I_0 / I_stall (10.6 % for Type I at 24 V, 21.6 % for Type II at 6 V),
      // eta_max = (1 - sqrt(I_0 / I_stall))^2: within 1 % of stall torque and 2 efficiency points
      // (the viscous loss b w^2 is about 1.8 % of the input at the Type I peak).
      const double ratio = i0 * res / v;  // I_0 / I_stall
      const double classical = std::sqrt(ratio) - ratio;
      const double eta_classical = std::pow(1.0 - std::sqrt(ratio), 2) * kt / ke;
      EXPECT_NEAR(peak, classical, 0.01) << type << " at " << v << " V";
      EXPECT_NEAR(eta_max, eta_classical, 0.02) << type << " at " << v << " V";
      if (frac == 1.0) {
        record(std::string("type") + type + "_eta_peak_torque_fraction", peak);
        record(std::string("type") + type + "_eta_peak_fraction_minus_closed_form", peak - peak_cf);
        record(std::string("type") + type + "_eta_max", eta_max);
        record(std::string("type") + type + "_eta_max_minus_closed_form", eta_max - eta_cf);
      }
    }
  }
}

TEST(Motor, CurrentIsNeverNegativeNoRegeneration) {
  const MotorParams m = mm::motor_type("I");
  // I_a = (V - K_e w) / R: at 12 V and 100 rad/s (12 - 3.84) / 7.03 = 1.16074 A.
  EXPECT_NEAR(mm::armature_current(m, {}, 12.0, 100.0), (12.0 - 3.84) / 7.03, 1e-14);
  // Back-emf above the supply: the driver does not regenerate, the current is clamped to 0.
  EXPECT_EQ(mm::armature_current(m, {}, 12.0, 400.0), 0.0);
  EXPECT_EQ(mm::armature_current(m, {}, 0.0, 10.0), 0.0);
  // Negative voltage is not a reverse drive either (no reversing modelled).
  EXPECT_EQ(mm::armature_current(m, {}, -12.0, 0.0), 0.0);
}

TEST(Motor, NoLoadCurrentTermIsFrictionThatOpposesMotion) {
  const MotorParams m = mm::motor_type("I");
  const double kt_i0 = m.torque_constant_NmA * m.no_load_current_A;  // 1.91e-3 N m
  // At standstill with no current the motor gives no torque (does not push backwards).
  EXPECT_EQ(mm::active_torque(m, 0.0, 0.0), 0.0);
  // Moving forward at speed: -K_T I_0 - b w (tanh(100 / 0.5) = 1); 1e-15 absolute.
  EXPECT_NEAR(mm::active_torque(m, 0.0, 100.0), -kt_i0 - 6e-7 * 100.0, 1e-15);
  // Moving backwards: the friction reverses and opposes the motion.
  EXPECT_NEAR(mm::active_torque(m, 0.0, -100.0), kt_i0 + 6e-7 * 100.0, 1e-15);
  // Smooth sign: at w = scale the friction is K_T I_0 tanh(1).
  EXPECT_NEAR(mm::active_torque(m, 0.0, 0.5), -kt_i0 * std::tanh(1.0) - 6e-7 * 0.5, 1e-15);
  // Inactive (open circuit): only the viscous drag -b w.
  EXPECT_NEAR(mm::inactive_torque(m, 250.0), -6e-7 * 250.0, 1e-18);
  EXPECT_EQ(mm::inactive_torque(m, 0.0), 0.0);
}

TEST(Motor, VoltageForTorqueInvertsTheModel) {
  // voltage_for_torque(tau, w) must give back tau through armature_current and active_torque
  // (as long as the current it implies is positive); 1e-15 N m absolute.
  for (const char* type : {"I", "II"}) {
    const MotorParams m = mm::motor_type(type);
    for (double w : {0.0, 0.3, 10.0, 200.0, 500.0}) {
      for (double tau : {1e-3, 5e-3, 1e-2}) {
        const double v = mm::voltage_for_torque(m, tau, w);
        const double back = mm::active_torque(m, mm::armature_current(m, {}, v, w), w);
        EXPECT_NEAR(back, tau, 1e-15) << type << " w = " << w << " tau = " << tau;
      }
    }
  }
}

TEST(Motor, SideTorqueOfPartlyActiveSidesAndItsInverse) {
  const MotorParams m = mm::motor_type("I");
  const double w = 200.0, i = 0.4;
  // All 8 active: 8 times one motor; none: 8 drags; 2.5 of 8 (relaxed): the mix.
  EXPECT_NEAR(mm::side_torque(m, 8.0, 8.0, i, w), 8.0 * mm::active_torque(m, i, w), 1e-15);
  EXPECT_NEAR(mm::side_torque(m, 0.0, 8.0, i, w), -8.0 * m.viscous_Nms * w, 1e-15);
  const double mixed = mm::side_torque(m, 2.5, 8.0, i, w);
  EXPECT_NEAR(mixed, 2.5 * mm::active_torque(m, i, w) - 5.5 * m.viscous_Nms * w, 1e-15);
  // torque_per_active gives back the active motor's torque from the side's.
  EXPECT_NEAR(mm::torque_per_active(m, mixed, 2.5, 8.0, w), mm::active_torque(m, i, w), 1e-15);
}

}  // namespace
