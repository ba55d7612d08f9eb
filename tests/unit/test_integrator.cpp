// CVODE adapter (plant_core/integrator.hpp) against a fine fixed-step RK4 reference.
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "model/dynamics.hpp"
#include "plant_core/integrator.hpp"
#include "tests/unit/test_support.hpp"

namespace {

using maptr::test::record;

namespace mm = maptr::model;
using maptr::plant_core::CvodeIntegrator;
using maptr::plant_core::rk4_step;

// Inputs of tick k: 0.3 s straight acceleration (all agents, equal voltages), then a hard left
// turn (2 left agents at a low voltage, every right agent at a rising voltage), with one right
// agent switching on and off every few ticks.
void inputs_for_tick(int k, mm::Inputs& u) {
  const int ns = static_cast<int>(u.active_L.size());
  const bool turning = k >= 30;
  for (int i = 0; i < ns; ++i) {
    u.active_L[i] = !turning || i < 2;
    u.active_R[i] = !turning || i < ns - 1 || k % 7 < 3;
    u.voltage_L[i] = turning ? 8.0 : 12.0;
    u.voltage_R[i] = turning ? 16.0 + 0.05 * k : 12.0;
  }
}

// Runs 1 s of 10 ms ticks with CVODE (options o) and with RK4 (1000 substeps per tick, h = 10 us;
// RK4 with 100 substeps agrees with it to 1e-14, so it is the exact solution here) and checks
// v_x, w and the energy drawn at every tick to `tol` relative (w relative to max(|w|, 0.01 rad/s)).
void compare_with_rk4(const maptr::plant_core::IntegratorOptions& o, double tol, const std::string& tag) {
  mm::RobotParams p;
  p.gross_mass_kg = 18.2;
  CvodeIntegrator cv(p, o);
  mm::Inputs u(p.per_side());
  mm::State x_cv{}, x_rk{};
  x_cv[mm::kVx] = x_rk[mm::kVx] = 0.5;  // rolling already: the rolling friction's atan is smooth there
  const double dt = 0.01;
  double err_v = 0.0, err_w = 0.0, err_e = 0.0;
  for (int k = 0; k < 100; ++k) {
    inputs_for_tick(k, u);
    cv.step(x_cv, u, k * dt, dt);
    rk4_step(p, u, x_rk, dt, 1000);
    const double e_cv = x_cv[mm::kEnergyL] + x_cv[mm::kEnergyR];
    const double e_rk = x_rk[mm::kEnergyL] + x_rk[mm::kEnergyR];
    const double w_scale = std::max(std::fabs(x_rk[mm::kW]), 0.01);
    EXPECT_NEAR(x_cv[mm::kVx], x_rk[mm::kVx], tol * std::fabs(x_rk[mm::kVx])) << tag << " tick " << k;
    EXPECT_NEAR(x_cv[mm::kW], x_rk[mm::kW], tol * w_scale) << tag << " tick " << k;
    EXPECT_NEAR(e_cv, e_rk, tol * e_rk) << tag << " tick " << k;
    err_v = std::max(err_v, std::fabs(x_cv[mm::kVx] - x_rk[mm::kVx]) / std::fabs(x_rk[mm::kVx]));
    err_w = std::max(err_w, std::fabs(x_cv[mm::kW] - x_rk[mm::kW]) / w_scale);
    err_e = std::max(err_e, std::fabs(e_cv - e_rk) / e_rk);
  }
  // The scenario must really speed up and turn.
  EXPECT_GT(x_rk[mm::kVx], 1.5);
  EXPECT_GT(x_rk[mm::kW], 1.5);
  for (int i = 0; i < mm::kStateSize; ++i)
    EXPECT_NEAR(x_cv[i], x_rk[i], tol * std::max(std::fabs(x_rk[i]), 1.0)) << tag << " state " << i;
  record(tag + "_vx_rel_err", err_v);
  record(tag + "_w_rel_err", err_w);
  record(tag + "_energy_rel_err", err_e);
}

TEST(Integrator, CvodeMatchesFineRk4TightTolerances) {
  // rtol 1e-10, absolute 1e-12 (x 1e2, 1e3 on the ledgers): within 1e-6 relative (measured ~1e-9).
  maptr::plant_core::IntegratorOptions o;
  o.rtol = 1e-10;
  o.atol_scale = 1e-12;
  compare_with_rk4(o, 1e-6, "cvode_tight_vs_rk4");
}

TEST(Integrator, CvodeMatchesFineRk4DefaultTolerances) {
  // The plant's defaults (rtol 1e-8, atol_scale 1e-9), re-initialised every tick, accumulate about
  // 1e-6 relative over 100 ticks on v_x, w and energy (measured up to 1.4e-6): tolerance 5e-6.
  compare_with_rk4({}, 5e-6, "cvode_default_vs_rk4");
}

TEST(Integrator, RestWithoutInputStaysAtRest) {
  mm::RobotParams p;
  CvodeIntegrator cv(p);
  mm::Inputs u(p.per_side());
  mm::State x{};
  for (int k = 0; k < 10; ++k) cv.step(x, u, k * 0.01, 0.01);
  for (int i = 0; i < mm::kStateSize; ++i) EXPECT_EQ(x[i], 0.0) << "state " << i;
}

TEST(Integrator, RefusesNonPositiveDt) {
  mm::RobotParams p;
  CvodeIntegrator cv(p);
  mm::Inputs u(p.per_side());
  mm::State x{};
  EXPECT_THROW(cv.step(x, u, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(cv.step(x, u, 0.0, -0.01), std::invalid_argument);
  EXPECT_THROW(cv.step(x, u, 0.0, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  try {
    cv.step(x, u, 0.0, -0.01);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("dt"), std::string::npos) << e.what();
  }
  // The integrator is still usable afterwards.
  EXPECT_NO_THROW(cv.step(x, u, 0.0, 0.01));
}

}  // namespace
