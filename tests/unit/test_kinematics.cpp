// Skid-steer kinematics (model/kinematics.hpp) and turning in place through the dynamics.
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "model/dynamics.hpp"
#include "model/kinematics.hpp"
#include "plant_core/integrator.hpp"
#include "tests/unit/test_support.hpp"

namespace {

using maptr::test::record;

namespace mm = maptr::model;

TEST(Kinematics, HandValues) {
  // a = 0.2 m, v_x = 1 m/s, w = 2 rad/s: v_L = 1 - 0.1 * 2 = 0.8, v_R = 1.2 m/s (1e-15).
  const mm::WheelSpeeds s = mm::to_wheels({1.0, 2.0}, 0.2);
  EXPECT_NEAR(s.v_L, 0.8, 1e-15);
  EXPECT_NEAR(s.v_R, 1.2, 1e-15);
  // Inverse: v_x = (0.5 + 1.5) / 2 = 1, w = (1.5 - 0.5) / 0.2 = 5.
  const mm::BodyVelocity b = mm::to_body({0.5, 1.5}, 0.2);
  EXPECT_NEAR(b.v_x, 1.0, 1e-15);
  EXPECT_NEAR(b.w, 5.0, 1e-14);
}

TEST(Kinematics, WheelRatesAndTheirBodyVelocity) {
  // a = 0.2 m, r = 0.05 m, v_x = 1 m/s, w = 2 rad/s: phidot = (1 -+ 0.2) / 0.05 = 16, 24 rad/s.
  const mm::WheelRates q = mm::to_wheel_rates({1.0, 2.0}, 0.2, 0.05);
  EXPECT_NEAR(q.phidot_L, 16.0, 1e-13);
  EXPECT_NEAR(q.phidot_R, 24.0, 1e-13);
  // Back: v_x = (16 + 24) 0.05 / 2 = 1 m/s, w = 0.05 (24 - 16) / 0.2 = 2 rad/s.
  const mm::BodyVelocity b = mm::body_from_rates({16.0, 24.0}, 0.2, 0.05);
  EXPECT_NEAR(b.v_x, 1.0, 1e-15);
  EXPECT_NEAR(b.w, 2.0, 1e-14);
}

TEST(Kinematics, SpeedFromRatesIsTheForwardPartOfTheBodyVelocity) {
  // r = 0.035 m, phidot = 200 and 300 rad/s: v_x = (200 + 300) 0.035 / 2 = 8.75 m/s, whatever
  // the track; equal and opposite rates give no forward speed.
  EXPECT_NEAR(mm::speed_from_rates({200.0, 300.0}, 0.035), 8.75, 1e-14);
  EXPECT_NEAR(mm::speed_from_rates({-40.0, 40.0}, 0.035), 0.0, 1e-15);
  for (double a : {0.2, 0.75})
    EXPECT_EQ(mm::speed_from_rates({200.0, 300.0}, 0.035), mm::body_from_rates({200.0, 300.0}, a, 0.035).v_x);
}

TEST(Kinematics, RoundTrip) {
  // to_body(to_wheels(x)) = x and to_wheels(to_body(s)) = s, to 1e-14 relative to the magnitudes.
  double worst = 0.0;
  for (double a : {0.1, 0.2, 0.75}) {
    for (double v : {-3.0, 0.0, 0.01, 2.5, 20.0}) {
      for (double w : {-4.0, 0.0, 0.3, 7.0}) {
        const mm::BodyVelocity back = mm::to_body(mm::to_wheels({v, w}, a), a);
        EXPECT_NEAR(back.v_x, v, 1e-14 * (1.0 + std::fabs(v)));
        EXPECT_NEAR(back.w, w, 1e-14 * (1.0 + std::fabs(w) + std::fabs(v) / a));
        worst = std::max({worst, std::fabs(back.v_x - v), std::fabs(back.w - w)});
        const mm::WheelSpeeds s{v, w};  // reuse the grid as wheel speeds
        const mm::WheelSpeeds s2 = mm::to_wheels(mm::to_body(s, a), a);
        EXPECT_NEAR(s2.v_L, v, 1e-14 * (1.0 + std::fabs(v) + std::fabs(w)));
        EXPECT_NEAR(s2.v_R, w, 1e-14 * (1.0 + std::fabs(v) + std::fabs(w)));
      }
    }
  }
  record("kinematics_round_trip_max_abs_err", worst);
}

TEST(Kinematics, PureRotationHasOppositeWheelSpeeds) {
  const mm::WheelSpeeds s = mm::to_wheels({0.0, 1.5}, 0.2);
  EXPECT_NEAR(s.v_L, -0.15, 1e-15);
  EXPECT_NEAR(s.v_R, 0.15, 1e-15);
  const mm::BodyVelocity b = mm::to_body({-0.3, 0.3}, 0.2);
  EXPECT_EQ(b.v_x, 0.0);
  EXPECT_NEAR(b.w, 3.0, 1e-15);
}

// A robot spinning in place (v_x = 0, w = w0, all motors free-wheeling) must turn in place:
// X, Y and v_x stay 0 (left and right rolling resistances and drags cancel exactly), theta grows.
// With k_s large the friction is Coulomb-like, so the yaw equation is
//   I_eff dw/dt = -M_c - c w,   M_c = sum_rows 4 mu_l (m g / N) |x_j| + (a/2) mu_s m g  (lateral + rolling),
//                               c   = N b a^2 / (4 r^2)                                   (inactive drag),
// giving w(t) = (w0 + M_c/c) e^{-c t / I_eff} - M_c / c and theta(t) = integral of w.
TEST(Kinematics, SpinInPlaceAgainstClosedForm) {
  mm::RobotParams p;  // N = 16, m = 13.2 kg, Type I
  p.k_s = 1e7;        // atan(k_s w x_j) within 1e-5 of pi/2 while |w x_j| > 0.03 m/s
  maptr::plant_core::CvodeIntegrator cv(p);
  const double w0 = 2.0;
  mm::State x{};
  x[mm::kW] = w0;
  mm::Inputs u(p.per_side());  // all inactive

  const double m = 13.2, g = 9.81, n = 16, a = 0.2, b = 0.08, r = 0.035, bv = 6e-7, mu_l = 0.1, mu_s = 0.01;
  const double sum_abs_xj = 2.0 * (0.5 * b + 1.5 * b);  // rows at +-b/2, +-3b/2
  const double m_c = 4.0 * mu_l * (m * g / n) * sum_abs_xj + 0.5 * a * mu_s * m * g;
  const double c = n * bv * a * a / (4.0 * r * r);
  const double i_w = 0.5 * 0.05 * r * r;
  const double i_eff = m * (0.32 * 0.32 + a * a) / 12.0 + n * i_w * a * a / (4.0 * r * r);
  const double k = c / i_eff, s = m_c / c;

  const double dt = 0.01;
  double max_err_theta = 0.0, max_err_w = 0.0;
  for (int i = 0; i < 20; ++i) {  // 0.2 s, while w stays above ~0.5 rad/s
    const double theta_before = x[mm::kTheta];
    cv.step(x, u, i * dt, dt);
    const double t = (i + 1) * dt;
    const double w_cf = (w0 + s) * std::exp(-k * t) - s;
    const double theta_cf = -(w0 + s) * std::expm1(-k * t) / k - s * t;
    EXPECT_GT(x[mm::kTheta], theta_before);
    // X, Y, v_x: exactly 0 by symmetry; 1e-12 allows for rounding.
    EXPECT_NEAR(x[mm::kX], 0.0, 1e-12);
    EXPECT_NEAR(x[mm::kY], 0.0, 1e-12);
    EXPECT_NEAR(x[mm::kVx], 0.0, 1e-12);
    // The atan deviation from pi/2 at k_s = 1e7 is below 2 / (pi * 1e7 * 0.5 * 0.04) = 3e-6 relative
    // to the friction: tolerance 1e-5 relative on theta and w.
    EXPECT_NEAR(x[mm::kTheta], theta_cf, 1e-5 * theta_cf) << t;
    EXPECT_NEAR(x[mm::kW], w_cf, 1e-5 * w_cf) << t;
    max_err_theta = std::max(max_err_theta, std::fabs(x[mm::kTheta] - theta_cf) / theta_cf);
    max_err_w = std::max(max_err_w, std::fabs(x[mm::kW] - w_cf) / w_cf);
  }
  EXPECT_GT(x[mm::kTheta], 0.2);
  record("spin_in_place_theta_rel_err", max_err_theta);
  record("spin_in_place_w_rel_err", max_err_w);
}

}  // namespace
