// The motors of Table 1 and the derived parameters (model/params.hpp). The ranges of what a
// scenario sets are the field table's (tests/unit/test_scenario.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "model/params.hpp"

namespace {

using maptr::model::MotorParams;
using maptr::model::ParamError;
using maptr::model::RobotParams;
using maptr::model::motor_type;

// Runs fn, which must throw ParamError naming `field` and `value` in what().
void expect_refusal(const std::function<void()>& fn, const std::string& field, const std::string& value) {
  try {
    fn();
  } catch (const ParamError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(field), std::string::npos) << "message '" << msg << "' does not name " << field;
    EXPECT_NE(msg.find(value), std::string::npos) << "message '" << msg << "' does not show " << value;
    return;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected ParamError for " << field << ", got another exception: " << e.what();
    return;
  }
  ADD_FAILURE() << "expected ParamError for " << field << " = " << value << ", nothing thrown";
}

TEST(Params, MotorTypesHoldTable1) {
  // Paper Table 1, SI units; exact (the values are literals on both sides).
  const MotorParams a = motor_type("I");
  EXPECT_EQ(a.type, "I");
  EXPECT_DOUBLE_EQ(a.rated_voltage_V, 24.0);
  EXPECT_DOUBLE_EQ(a.no_load_current_A, 50e-3);
  EXPECT_DOUBLE_EQ(a.no_load_speed_rpm, 5930.0);
  EXPECT_DOUBLE_EQ(a.stall_torque_Nm, 130e-3);
  EXPECT_DOUBLE_EQ(a.resistance_ohm, 7.03);
  EXPECT_DOUBLE_EQ(a.viscous_Nms, 6e-7);
  EXPECT_DOUBLE_EQ(a.torque_constant_NmA, 38.2e-3);
  EXPECT_DOUBLE_EQ(a.back_emf_Vs, 38.4e-3);
  EXPECT_DOUBLE_EQ(a.mass_kg, 0.21);
  const MotorParams b = motor_type("II");
  EXPECT_EQ(b.type, "II");
  EXPECT_DOUBLE_EQ(b.rated_voltage_V, 6.0);
  EXPECT_DOUBLE_EQ(b.no_load_current_A, 250e-3);
  EXPECT_DOUBLE_EQ(b.no_load_speed_rpm, 5500.0);
  EXPECT_DOUBLE_EQ(b.stall_torque_Nm, 17.6e-3);
  EXPECT_DOUBLE_EQ(b.resistance_ohm, 2.4);
  EXPECT_DOUBLE_EQ(b.viscous_Nms, 2.2e-7);
  EXPECT_DOUBLE_EQ(b.torque_constant_NmA, 7e-3);
  EXPECT_DOUBLE_EQ(b.back_emf_Vs, 7e-3);
  EXPECT_DOUBLE_EQ(b.mass_kg, 0.11);
}

TEST(Params, UnknownMotorTypesAreRefused) {
  expect_refusal([] { motor_type("III"); }, "motor.type", "III");  // no data in the paper
  expect_refusal([] { motor_type("X"); }, "motor.type", "X");
  expect_refusal([] { motor_type("i"); }, "motor.type", "i");
}

TEST(Params, DerivedInertiasAndRowOffsets) {
  // I_zz = m ((N/4 b)^2 + a^2) / 12 with m = 13.2, N = 16, b = 0.08, a = 0.2:
  //      = 13.2 (0.32^2 + 0.2^2) / 12 = 13.2 * 0.1424 / 12 = 0.15664 kg m^2 (exact decimal, 1e-15 tol).
  RobotParams p;
  EXPECT_NEAR(p.yaw_inertia(), 0.15664, 1e-15);
  // I_w = m_w r^2 / 2 = 0.05 * 0.035^2 / 2 = 3.0625e-5 kg m^2.
  EXPECT_NEAR(p.wheel_inertia(), 3.0625e-5, 1e-18);
  // Explicit values override the derived ones.
  p.yaw_inertia_kgm2 = 0.5;
  p.wheel_inertia_kgm2 = 1e-4;
  EXPECT_DOUBLE_EQ(p.yaw_inertia(), 0.5);
  EXPECT_DOUBLE_EQ(p.wheel_inertia(), 1e-4);

  // Rows centred, b apart: N = 16 -> -3b/2, -b/2, b/2, 3b/2; N = 4 -> 0; N = 8 -> +-b/2.
  RobotParams q;
  EXPECT_EQ(q.per_side(), 8);
  EXPECT_EQ(q.rows(), 4);
  const double b = q.row_spacing_m;
  EXPECT_NEAR(q.row_offset(0), -1.5 * b, 1e-15);
  EXPECT_NEAR(q.row_offset(1), -0.5 * b, 1e-15);
  EXPECT_NEAR(q.row_offset(2), 0.5 * b, 1e-15);
  EXPECT_NEAR(q.row_offset(3), 1.5 * b, 1e-15);
  q.agents = 4;
  EXPECT_NEAR(q.row_offset(0), 0.0, 1e-15);
  q.agents = 8;
  EXPECT_NEAR(q.row_offset(0), -0.5 * b, 1e-15);
  EXPECT_NEAR(q.row_offset(1), 0.5 * b, 1e-15);
  // N = 64: I_zz = 13.2 ((16 * 0.08)^2 + 0.04) / 12 = 13.2 * 1.6784 / 12 = 1.84624.
  q.agents = 64;
  EXPECT_NEAR(q.yaw_inertia(), 1.84624, 1e-14);
}

}  // namespace
