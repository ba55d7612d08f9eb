// The motor driver (model/params.hpp DriverParams, model/motor.hpp, model/dynamics.hpp
// side_load): an H-bridge's four quadrants against the closed forms, braking power dissipated
// or returned to the battery within its charge limit, and the energy balance while braking.
#include <gtest/gtest.h>

#include <cmath>

#include "model/dynamics.hpp"
#include "model/motor.hpp"
#include "plant_core/integrator.hpp"

namespace {

namespace mm = maptr::model;

mm::DriverParams h_bridge(bool regen = false, double limit_A = 5.0) {
  mm::DriverParams d;
  d.bidirectional = true;
  d.regeneration = regen;
  d.charge_limit_A = limit_A;
  return d;
}

TEST(Driver, FourQuadrantsOfTheHBridgeAgainstTheClosedForm) {
  const mm::MotorParams m = mm::motor_type("I");
  const mm::DriverParams d = h_bridge();
  const double ke = 38.4e-3, r = 7.03;
  struct Case {
    double volts, phidot;
    int current_sign, torque_sign;
  } cases[] = {
      {12.0, 100.0, +1, +1},   // I: driving forward
      {1.0, 100.0, -1, -1},    // II: V below the back-EMF: braking (generating)
      {-12.0, -100.0, -1, -1}, // III: driving backwards
      {-1.0, -100.0, +1, +1},  // IV: braking while rolling backwards
  };
  for (const auto& c : cases) {
    const double i = mm::armature_current(m, d, c.volts, c.phidot);
    EXPECT_NEAR(i, (c.volts - ke * c.phidot) / r, 1e-14) << c.volts << " V, " << c.phidot << " rad/s";
    EXPECT_EQ(i > 0 ? 1 : -1, c.current_sign);
    const double tau = mm::active_torque(m, i, c.phidot);
    EXPECT_EQ(tau > 0 ? 1 : -1, c.torque_sign);
  }
  // The unidirectional driver clamps the braking quadrant to no current.
  EXPECT_EQ(mm::armature_current(m, mm::DriverParams{}, 1.0, 100.0), 0.0);
  EXPECT_EQ(mm::armature_current(m, mm::DriverParams{}, -12.0, 0.0), 0.0);
}

TEST(Driver, BrakingPowerIsDissipatedOrReturnedWithinTheChargeLimit) {
  const mm::MotorParams m = mm::motor_type("I");
  const double phidot = 200.0, volts = 2.0;  // back-EMF 7.68 V: generating
  const double i = (volts - 38.4e-3 * phidot) / 7.03;  // < 0
  const std::vector<double> v(4, volts);
  const std::vector<uint8_t> on(4, 1);
  // Dissipated: nothing drawn, nothing returned, -4 V I in the driver.
  const mm::SideLoad dis = mm::side_load(m, h_bridge(false), v, on, phidot);
  EXPECT_EQ(dis.power_W, 0.0);
  EXPECT_EQ(dis.current_A, 0.0);
  EXPECT_NEAR(dis.driver_W, -4.0 * volts * i, 1e-12);
  EXPECT_NEAR(dis.joule_W, 4.0 * i * i * 7.03 + dis.driver_W, 1e-12);
  // Returned, under the limit: the battery is charged with 4 |I| at power 4 V I (< 0).
  const mm::SideLoad back = mm::side_load(m, h_bridge(true, 100.0), v, on, phidot);
  EXPECT_NEAR(back.power_W, 4.0 * volts * i, 1e-12);
  EXPECT_NEAR(back.current_A, 4.0 * i, 1e-12);
  EXPECT_EQ(back.driver_W, 0.0);
  // Returned above the limit: the battery takes limit / (4 |I|) of it, the driver the rest.
  const double limit = 0.5;
  const mm::SideLoad capped = mm::side_load(m, h_bridge(true, limit), v, on, phidot);
  EXPECT_NEAR(capped.current_A, -limit, 1e-12);
  const double share = limit / (4.0 * std::fabs(i));
  EXPECT_NEAR(capped.power_W, share * 4.0 * volts * i, 1e-12);
  EXPECT_NEAR(capped.driver_W, -(1.0 - share) * 4.0 * volts * i, 1e-12);
  // Torque is the motor's in every case: the driver decides only where the power goes.
  EXPECT_EQ(dis.torque_Nm, back.torque_Nm);
  EXPECT_LT(dis.torque_Nm, 0.0);
}

TEST(Driver, EfficiencyOfBraking) {
  const mm::MotorParams m = mm::motor_type("I");
  // Generating: 0 when dissipated, (V I) / (tau phidot) in (0, 1) when returned.
  EXPECT_EQ(mm::efficiency(m, h_bridge(false), 2.0, 200.0), 0.0);
  const double eta = mm::efficiency(m, h_bridge(true), 2.0, 200.0);
  const double i = (2.0 - 38.4e-3 * 200.0) / 7.03;
  EXPECT_NEAR(eta, (2.0 * i) / (mm::active_torque(m, i, 200.0) * 200.0), 1e-12);
  EXPECT_GT(eta, 0.0);
  EXPECT_LT(eta, 1.0);
  // Driving: the same as the unidirectional driver's.
  EXPECT_EQ(mm::efficiency(m, h_bridge(), 12.0, 100.0), mm::efficiency(m, mm::DriverParams{}, 12.0, 100.0));
}

TEST(Driver, EnergyBalanceWhileBrakingAndRegenerating) {
  // Battery energy = Joule (windings + driver) + mechanical losses + K_e/K_T mismatch + kinetic,
  // while one side brakes hard: with and without regeneration.
  for (bool regen : {false, true}) {
    mm::RobotParams p;
    p.gross_mass_kg = 30.0;
    p.driver = h_bridge(regen, 1.0);
    maptr::plant_core::CvodeIntegrator cv(p);
    mm::Inputs u(8);
    mm::State x{};
    const double dt = 0.01;
    double braked = 0.0;
    for (int k = 0; k < 2000; ++k) {  // 20 s: 8 s at 20 V, then the left side at -6 V (braking)
      const double t = k * dt;
      for (int i = 0; i < 8; ++i) {
        u.active_L[i] = u.active_R[i] = 1;
        u.voltage_L[i] = t < 8 ? 20.0 : -6.0;
        u.voltage_R[i] = t < 8 ? 20.0 : 2.0;
      }
      const double before = x[mm::kEnergyR];  // the right side at 2 V: below its back-EMF
      cv.step(x, u, t, dt);
      if (t >= 8) braked += std::min(0.0, x[mm::kEnergyR] - before);
      const double drawn = x[mm::kEnergyL] + x[mm::kEnergyR];
      const double accounted = x[mm::kLossJoule] + x[mm::kLossMech] + x[mm::kLossEmf] +
                               mm::kinetic_energy(p, x[mm::kVx], x[mm::kW]);
      ASSERT_NEAR(accounted, drawn, 1e-5 * std::fabs(x[mm::kLossJoule]) + 1e-6) << "t = " << t << ", regen " << regen;
    }
    EXPECT_GT(std::fabs(x[mm::kTheta]), 0.5);  // it really turned
    if (regen)
      EXPECT_LT(braked, 0.0);  // the battery took energy back at some tick
    else
      EXPECT_EQ(braked, 0.0);
  }
}

}  // namespace
