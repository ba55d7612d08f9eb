// Parameter validation and derived parameters (model/params.hpp).
// Every refusal must throw model::ParamError whose message names the field and the bad value.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "model/params.hpp"

namespace {

using maptr::model::BatteryParams;
using maptr::model::MotorParams;
using maptr::model::ParamError;
using maptr::model::PidParams;
using maptr::model::RobotParams;
using maptr::model::motor_type;

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

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

// Validates a copy of the default robot after `change` was applied to it.
void expect_robot_refusal(const std::function<void(RobotParams&)>& change, const std::string& field,
                          const std::string& value) {
  expect_refusal(
      [&] {
        RobotParams p;
        change(p);
        p.validate();
      },
      field, value);
}

TEST(Params, DefaultsAndBothMotorTypesValidate) {
  EXPECT_NO_THROW(RobotParams{}.validate());
  EXPECT_NO_THROW(PidParams{}.validate());
  EXPECT_NO_THROW(motor_type("I").validate());
  EXPECT_NO_THROW(motor_type("II").validate());
  RobotParams p;
  p.motor = motor_type("II");
  EXPECT_NO_THROW(p.validate());
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
  expect_robot_refusal([](RobotParams& p) { p.motor.type = "X"; }, "motor.type", "X");
  expect_robot_refusal([](RobotParams& p) { p.motor.type = "III"; }, "motor.type", "III");
}

TEST(Params, AgentsMustBeAMultipleOf4Within4To512) {
  for (int n : {4, 8, 16, 64, 128, 512}) {
    RobotParams p;
    p.agents = n;
    EXPECT_NO_THROW(p.validate()) << n;
  }
  for (int n : {6, 10, 18, 3, 1}) expect_robot_refusal([n](RobotParams& p) { p.agents = n; }, "agents", std::to_string(n));
  for (int n : {0, -4, 516, 1024}) expect_robot_refusal([n](RobotParams& p) { p.agents = n; }, "agents", std::to_string(n));
}

TEST(Params, MassRefusals) {
  expect_robot_refusal([](RobotParams& p) { p.gross_mass_kg = -1.0; }, "gross_mass_kg", "-1");
  expect_robot_refusal([](RobotParams& p) { p.gross_mass_kg = 0.0; }, "gross_mass_kg", "0");
  expect_robot_refusal([](RobotParams& p) { p.gross_mass_kg = kNaN; }, "gross_mass_kg", "nan");
  expect_robot_refusal([](RobotParams& p) { p.gross_mass_kg = kInf; }, "gross_mass_kg", "inf");
  expect_robot_refusal([](RobotParams& p) { p.wheel_mass_kg = -0.05; }, "wheel_mass_kg", "-0.05");
}

TEST(Params, GeometryAndFrictionRefusals) {
  expect_robot_refusal([](RobotParams& p) { p.wheel_radius_m = 0.0; }, "wheel_radius_m", "0");
  expect_robot_refusal([](RobotParams& p) { p.wheel_radius_m = -0.035; }, "wheel_radius_m", "-0.035");
  expect_robot_refusal([](RobotParams& p) { p.track_m = 0.0; }, "track_m", "0");
  expect_robot_refusal([](RobotParams& p) { p.row_spacing_m = -0.08; }, "row_spacing_m", "-0.08");
  expect_robot_refusal([](RobotParams& p) { p.mu_rolling = -0.01; }, "mu_rolling", "-0.01");
  expect_robot_refusal([](RobotParams& p) { p.mu_lateral = kNaN; }, "mu_lateral", "nan");
  expect_robot_refusal([](RobotParams& p) { p.k_s = 0.0; }, "k_s", "0");
  expect_robot_refusal([](RobotParams& p) { p.gravity = -9.81; }, "gravity", "-9.81");
  expect_robot_refusal([](RobotParams& p) { p.yaw_inertia_kgm2 = kNaN; }, "yaw_inertia_kgm2", "nan");
  expect_robot_refusal([](RobotParams& p) { p.wheel_inertia_kgm2 = kInf; }, "wheel_inertia_kgm2", "inf");
}

TEST(Params, MotorBatteryAndPidRefusals) {
  expect_robot_refusal([](RobotParams& p) { p.motor.resistance_ohm = 0.0; }, "motor.resistance_ohm", "0");
  expect_robot_refusal([](RobotParams& p) { p.motor.torque_constant_NmA = -0.0382; }, "motor.torque_constant_NmA",
                       "-0.0382");
  expect_robot_refusal([](RobotParams& p) { p.motor.back_emf_Vs = kNaN; }, "motor.back_emf_Vs", "nan");
  expect_robot_refusal([](RobotParams& p) { p.motor.no_load_current_A = -0.05; }, "motor.no_load_current_A",
                       "-0.05");
  expect_robot_refusal([](RobotParams& p) { p.motor.viscous_Nms = -6e-07; }, "motor.viscous_Nms", "-6e-07");
  expect_robot_refusal([](RobotParams& p) { p.motor.rated_voltage_V = 0.0; }, "motor.rated_voltage_V", "0");
  expect_robot_refusal([](RobotParams& p) { p.motor.friction_sign_scale_rad_s = 0.0; },
                       "motor.friction_sign_scale_rad_s", "0");
  expect_robot_refusal([](RobotParams& p) { p.battery.capacity_mAh = -6395.0; }, "battery.capacity_mAh", "-6395");
  expect_robot_refusal([](RobotParams& p) { p.battery.y = 0.0; }, "battery.y", "0");
  expect_refusal(
      [] {
        PidParams g;
        g.kp = -0.5;
        g.validate();
      },
      "pid.kp", "-0.5");
  expect_refusal(
      [] {
        PidParams g;
        g.ki = kNaN;
        g.validate();
      },
      "pid.ki", "nan");
  expect_refusal(
      [] {
        PidParams g;
        g.kp = 0.0;
        g.ki = 0.0;
        g.validate();
      },
      "pid.kp", "0");
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
