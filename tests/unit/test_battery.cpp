// Battery model V_B(d) = h e^{w d} + y e^{z d} (model/battery.hpp), d in mAh.
#include <gtest/gtest.h>

#include <cmath>

#include "model/battery.hpp"

namespace {

using maptr::model::BatteryParams;
using maptr::model::battery_voltage;

// The paper's fit coefficients, written out here rather than read from BatteryParams.
constexpr double kH = -1.851e-14, kW = 0.005345, kY = 23.4, kZ = -1.018e-5;

double by_hand(double d) { return kH * std::exp(kW * d) + kY * std::exp(kZ * d); }

TEST(Battery, VoltageAgainstTheFormula) {
  const BatteryParams b;
  // d = 0: h + y = 23.4 - 1.851e-14 V; tolerance 1e-12 V.
  EXPECT_NEAR(battery_voltage(b, 0.0), 23.4, 1e-12);
  // Hand values (exponentials evaluated separately):
  //   d = 3000: -1.851e-14 e^{16.035} + 23.4 e^{-0.03054} = -1.7e-7 + 22.69617 = 22.696166 V
  //   d = 6000: -1.851e-14 e^{32.07}  + 23.4 e^{-0.06108} = -1.56758 + 22.01350 = 20.445920 V
  //   d = 6395: -1.851e-14 e^{34.181} + 23.4 e^{-0.065101} = -12.94630 + 21.92516 = 8.978866 V
  // Tolerance 1e-6 V against the 7-digit hand values, 1e-12 relative against the formula.
  EXPECT_NEAR(battery_voltage(b, 3000.0), 22.696166, 1e-6);
  EXPECT_NEAR(battery_voltage(b, 6000.0), 20.445920, 1e-6);
  EXPECT_NEAR(battery_voltage(b, 6395.0), 8.978866, 1e-6);
  EXPECT_NEAR(battery_voltage(b, 6395.0), 9.0, 0.05);
  for (double d : {0.0, 1000.0, 3000.0, 5000.0, 6000.0, 6395.0})
    EXPECT_NEAR(battery_voltage(b, d), by_hand(d), 1e-12 * std::fabs(by_hand(d))) << d;
}

TEST(Battery, DecreasesWithDischargeAndNeverGoesNegative) {
  const BatteryParams b;
  double prev = battery_voltage(b, 0.0);
  for (double d = 10.0; d <= 8000.0; d += 10.0) {
    const double v = battery_voltage(b, d);
    EXPECT_LE(v, prev) << d;
    EXPECT_GE(v, 0.0) << d;
    prev = v;
  }
  // Past the knee the fit goes negative (at 7000 mAh: -1.851e-14 e^{37.415} + 21.79 = -306.7 V);
  // the model clamps it to 0 V.
  EXPECT_LT(by_hand(7000.0), 0.0);
  EXPECT_EQ(battery_voltage(b, 7000.0), 0.0);
}

}  // namespace
