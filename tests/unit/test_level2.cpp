// Level 2 (control/level2/problem.hpp: objective and oracle; control/level2/solver.hpp: Ipopt).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "control/level2/problem.hpp"
#include "control/level2/solver.hpp"
#include "model/motor.hpp"

namespace {

using maptr::control::exhaustive_level2;
using maptr::control::feasibility_voltage;
using maptr::control::horizon_efficiency;
using maptr::control::level2_feasible;
using maptr::control::Level2Choice;
using maptr::control::Level2Problem;
using maptr::control::Level2Result;
using maptr::control::Level2Solver;
using maptr::control::required_voltage;

/// Straight line at the reference speed (steady), left side, other side unknown (symmetric).
Level2Problem straight(int agents, double mass_kg, double speed_m_s, double battery_V,
                       double start_fraction = 1.0) {
  Level2Problem p;
  p.robot.agents = agents;
  p.robot.gross_mass_kg = mass_kg;
  p.side = 0;
  p.live = p.robot.per_side();
  p.n_other = 0.0;
  p.v_x = start_fraction * speed_m_s;
  p.w = 0.0;
  p.phidot_ref_L = p.phidot_ref_R = speed_m_s / p.robot.wheel_radius_m;
  p.battery_V = battery_V;
  p.validate();
  return p;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

TEST(Level2Oracle, MoreLoadNeverFewerAgents) {
  int prev = 0;
  for (double m = 8.0; m <= 40.0 + 1e-9; m += 0.5) {
    const Level2Choice c = exhaustive_level2(straight(16, m, 10.0, 23.4));
    ASSERT_TRUE(c.feasible) << "m = " << m;
    EXPECT_GE(c.n_active, prev) << "m = " << m;
    prev = c.n_active;
  }
  EXPECT_GT(prev, 1);
}

TEST(Level2Oracle, InfeasibleLoadRunsAllLiveAgents) {
  Level2Problem p = straight(16, 2000.0, 10.0, 23.4);
  p.live = 6;  // two agents of the side have failed
  const Level2Choice c = exhaustive_level2(p);
  EXPECT_FALSE(c.feasible);
  EXPECT_EQ(c.n_active, 6);

  Level2Solver solver;
  const Level2Result r = solver.solve(p);
  EXPECT_FALSE(r.feasible);
  EXPECT_EQ(r.n_active, 6);
}

TEST(Level2Model, RequiredVoltageClosedForm) {
  for (int agents : {8, 16, 64}) {
    for (double mass : {9.0, 13.2, 38.2}) {
      for (double speed : {5.0, 10.0, 20.0}) {
        const Level2Problem p = straight(agents, mass, speed, 23.4);
        const auto& rb = p.robot;
        const auto& mo = rb.motor;
        const double phidot = speed / rb.wheel_radius_m;
        // Straight line in steady state: F_rx r = tau_L + tau_R, equal sides.
        const double f_rx = rb.mu_rolling * mass * rb.gravity * (2.0 / M_PI) * std::atan(rb.k_s * speed);
        for (double n : {1.0, 2.5, 4.0}) {
          // Active motors give the side's share of F_rx r plus the inactive motors' drag.
          const double tau_side =
              0.5 * f_rx * rb.wheel_radius_m + (rb.per_side() - n) * mo.viscous_Nms * phidot;
          const double expected =
              mo.back_emf_Vs * phidot +
              mo.resistance_ohm * (tau_side / n / mo.torque_constant_NmA + mo.no_load_current_A +
                                   mo.viscous_Nms * phidot / mo.torque_constant_NmA);
          EXPECT_NEAR(required_voltage(p, n), expected, 1e-6 * expected)
              << "N " << agents << " m " << mass << " v " << speed << " n " << n;
        }
      }
    }
  }
}

TEST(Level2Model, EfficiencyBoundsAndPartialActivationPays) {
  const Level2Problem p = straight(16, 13.2, 10.0, 23.4);
  for (double n = 1.0; n <= p.live; n += 0.25) {
    const double j = horizon_efficiency(p, n);
    EXPECT_GE(j, 0.0);
    EXPECT_LE(j, p.horizon);
  }
  // A transient (starting at 80 % of the reference) stays in bounds too.
  const Level2Problem q = straight(16, 13.2, 10.0, 23.4, 0.8);
  for (int n = 1; n <= q.live; ++n) {
    const double j = horizon_efficiency(q, n);
    EXPECT_GE(j, 0.0);
    EXPECT_LE(j, q.horizon);
  }
  const Level2Choice c = exhaustive_level2(p);
  ASSERT_TRUE(c.feasible);
  EXPECT_LT(c.n_active, p.live);
  const double eta_opt = horizon_efficiency(p, c.n_active) / p.horizon;
  const double eta_all = horizon_efficiency(p, p.live) / p.horizon;
  EXPECT_GT(eta_opt, eta_all + 0.05);
}

TEST(Level2Model, TransientRolloutConvergesToSteadyState) {
  // Starting at the reference, the rollout holds it: J = H * steady-state efficiency.
  const Level2Problem p = straight(16, 20.0, 10.0, 23.4);
  for (int n : {2, 4, 8}) {
    const double v = required_voltage(p, n);
    const double eta_ss = maptr::model::efficiency(p.robot.motor, {}, v, p.phidot_ref_L);
    EXPECT_NEAR(horizon_efficiency(p, n), p.horizon * eta_ss, 1e-6) << "n " << n;
  }
}

/// Ipopt's integer choice vs the oracle over loads, speeds, battery voltages, N and the start
/// speed (at the reference, or 10 % below it: a transient). Fresh solver per case (cold start).
void compare_on_grid(const maptr::control::Level2SolverConfig& config, const char* name) {
  int cases = 0, differ = 0, feasible_cases = 0, max_gap = 0;
  std::vector<double> times;
  for (int agents : {8, 16, 32, 64}) {
    for (double mass_per_agent : {0.6, 1.0, 1.6, 2.4}) {  // gross 4.8..153.6 kg
      const double mass = mass_per_agent * agents;
      for (double speed : {5.0, 8.0, 11.0, 14.0, 18.0}) {
        for (double volt : {12.0, 16.0, 20.0, 23.4}) {
          for (double start : {1.0, 0.9}) {
            const Level2Problem p = straight(agents, mass, speed, volt, start);
            const Level2Choice oracle = exhaustive_level2(p);
            Level2Solver solver(config);
            const Level2Result r = solver.solve(p);
            times.push_back(r.solve_time_ms);
            ++cases;
            feasible_cases += oracle.feasible;
            EXPECT_EQ(r.feasible, oracle.feasible);
            const int gap = std::abs(r.n_active - oracle.n_active);
            max_gap = std::max(max_gap, gap);
            if (gap != 0) {
              ++differ;
              std::printf(
                  "[ Level2 ] differ: N %d m %.1f v %.0f V %.1f start %.1f: ipopt %d (%.3f, st %d)"
                  " oracle %d  J %.6f vs %.6f\n",
                  agents, mass, speed, volt, start, r.n_active, r.n_relaxed, r.ipopt_status, oracle.n_active,
                  r.objective, oracle.objective);
            }
          }
        }
      }
    }
  }
  const double rate = static_cast<double>(differ) / cases;
  std::printf(
      "[ Level2 ] %s: Ipopt vs oracle: %d of %d cases differ (%.1f %%), max gap %d, "
      "%d feasible; median solve %.2f ms, max %.2f ms\n",
      name, differ, cases, 100.0 * rate, max_gap, feasible_cases, median(times),
      *std::max_element(times.begin(), times.end()));
  EXPECT_LE(rate, 0.10);
  EXPECT_LE(max_gap, 1);
}

TEST(Level2Solver, IpoptMatchesOracleOnGrid) { compare_on_grid({}, "fd hessian"); }

TEST(Level2Solver, IpoptLimitedMemoryMatchesOracleOnGrid) {
  maptr::control::Level2SolverConfig c;
  c.fd_hessian = false;
  compare_on_grid(c, "limited-memory");
}

TEST(Level2Solver, IpoptMatchesOracleInTurns) {
  // Both sides of turns of several radii (inner side slower), steady and transient.
  int cases = 0, differ = 0;
  for (int agents : {16, 32}) {
    for (double mass : {15.0, 30.0}) {
      for (double radius_m : {0.3, 1.0, 5.0}) {
        for (int side : {0, 1}) {
          for (double start : {1.0, 0.9}) {
            Level2Problem p = straight(agents, mass, 8.0, 23.4);
            const double v = 4.0, w = v / radius_m, a = p.robot.track_m, r = p.robot.wheel_radius_m;
            p.phidot_ref_L = (v - 0.5 * a * w) / r;
            p.phidot_ref_R = (v + 0.5 * a * w) / r;
            p.v_x = start * v;
            p.w = start * w;
            p.side = side;
            p.n_other = 3.0;
            const Level2Choice oracle = exhaustive_level2(p);
            Level2Solver solver;
            const Level2Result res = solver.solve(p);
            ++cases;
            EXPECT_EQ(res.feasible, oracle.feasible);
            EXPECT_LE(std::abs(res.n_active - oracle.n_active), 1);
            if (res.n_active != oracle.n_active) {
              ++differ;
              std::printf(
                  "[ Level2 ] turn differ: N %d m %.0f R %.1f side %d start %.1f: ipopt %d (%.3f)"
                  " oracle %d J %.6f vs %.6f\n",
                  agents, mass, radius_m, side, start, res.n_active, res.n_relaxed, oracle.n_active,
                  res.objective, oracle.objective);
            }
          }
        }
      }
    }
  }
  std::printf("[ Level2 ] turns: %d of %d differ\n", differ, cases);
  EXPECT_LE(differ, cases / 10);
}

TEST(Level2Solver, WarmStartFollowsSlowlyChangingLoad) {
  // One solver reused (as in the group process), warm-started from its previous solution.
  for (int agents : {16, 64}) {
    Level2Solver solver;
    int differ = 0, n = 0;
    std::vector<double> times;
    for (double m = 0.5 * agents; m <= 2.5 * agents + 1e-9; m += 0.0625 * agents, ++n) {
      const Level2Problem p = straight(agents, m, 10.0, 23.4);
      const Level2Result r = solver.solve(p);
      times.push_back(r.solve_time_ms);
      differ += r.n_active != exhaustive_level2(p).n_active;
    }
    EXPECT_EQ(differ, 0) << "of " << n;
    std::printf("[ Level2 ] warm-started, N %d: %d of %d differ, median solve %.2f ms\n", agents, differ, n,
                median(times));
  }
}

}  // namespace

namespace {

/// The cruise decisions of the `weights` and `voltages` experiments (16 agents, straight line):
/// one solver per family, reused and warm-started; the side alternates and the speed wanders
/// by +-wander around the reference from one decision to the next.
int cruise_disagreements(int decisions, double wander) {
  struct Family {
    double mass_kg, speed_mps, battery_V;
  };
  const Family families[] = {{13.2, 10.0, 23.4}, {23.2, 10.0, 23.4}, {33.2, 10.0, 23.4}, {14.4, 8.0, 12.0},
                             {14.4, 8.0, 16.0},  {14.4, 8.0, 20.0},  {14.4, 8.0, 23.4}};
  int differ = 0;
  for (const Family& f : families) {
    Level2Solver solver;
    for (int i = 0; i < decisions; ++i) {
      Level2Problem p = straight(16, f.mass_kg, f.speed_mps, f.battery_V, 1.0 + wander * std::sin(0.7 * i));
      p.side = i % 2;
      const Level2Result r = solver.solve(p);
      const Level2Choice oracle = exhaustive_level2(p);
      EXPECT_EQ(r.feasible, oracle.feasible);
      if (r.n_active != oracle.n_active) {
        ++differ;
        std::printf("[ Level2 ] cruise differ: m %.1f V %.1f i %d: ipopt %d (%.4f, st %d) oracle %d\n",
                    f.mass_kg, f.battery_V, i, r.n_active, r.n_relaxed, r.ipopt_status, oracle.n_active);
      }
    }
  }
  return differ;
}

}  // namespace

TEST(Level2Solver, WarmStartedCruiseEqualsOracleAtEveryDecision) {
  // Each solve starts from the previous one's solution and multipliers.
  EXPECT_EQ(cruise_disagreements(100, 0.03), 0);
}

TEST(Level2Solver, ReusedSolverRecoversAfterInfeasibleAndFewerLiveAgents) {
  // One solver (one Ipopt NLP, re-optimised) through a feasible decision, an infeasible one
  // (Ipopt does not converge there), fewer live agents and back: each as the oracle decides.
  Level2Solver solver;
  const Level2Problem normal = straight(16, 20.0, 10.0, 23.4);
  Level2Problem heavy = straight(16, 2000.0, 10.0, 23.4);
  Level2Problem failed = normal;
  failed.live = 5;
  for (const Level2Problem& p : {normal, heavy, failed, normal, heavy, normal}) {
    const Level2Result r = solver.solve(p);
    const Level2Choice oracle = exhaustive_level2(p);
    EXPECT_EQ(r.feasible, oracle.feasible) << "mass " << p.robot.gross_mass_kg << " live " << p.live;
    EXPECT_EQ(r.n_active, oracle.n_active) << "mass " << p.robot.gross_mass_kg << " live " << p.live;
    EXPECT_NE(r.ipopt_status, maptr::control::kLevel2InitFailed);
  }
}

namespace {

/// One side of a steady left turn of radius 4 m at 1 m/s, 16 agents, 30 kg.
Level2Problem turn_side(int side, bool bidirectional) {
  Level2Problem p;
  p.robot.gross_mass_kg = 30.0;
  p.robot.driver.bidirectional = bidirectional;
  p.side = side;
  p.live = p.robot.per_side();
  p.v_x = 1.0;
  p.w = 0.25;
  const double a = p.robot.track_m, r = p.robot.wheel_radius_m;
  p.phidot_ref_L = (1.0 - 0.5 * a * 0.25) / r;
  p.phidot_ref_R = (1.0 + 0.5 * a * 0.25) / r;
  return p;
}

TEST(Level2, ABrakingSideRunsEveryLiveAgentInTheOracleAndTheSolverAlike) {
  // The inner (left) side of a tight turn must brake: with the H-bridge every live agent runs.
  const Level2Problem inner = turn_side(0, true);
  EXPECT_LT(maptr::control::steady_side_torque(inner), 0.0);
  ASSERT_TRUE(maptr::control::braking_demand(inner));
  EXPECT_LT(required_voltage(inner, inner.live), 0.0);  // it drives against the motion
  const Level2Choice o = exhaustive_level2(inner);
  EXPECT_EQ(o.n_active, inner.live);
  EXPECT_TRUE(o.feasible);
  Level2Solver solver;
  const Level2Result s = solver.solve(inner);
  EXPECT_EQ(s.n_active, inner.live);
  EXPECT_TRUE(s.feasible);
  EXPECT_EQ(s.ipopt_status, maptr::control::kLevel2NotSolved);
  // A side that drives, and the unidirectional driver (it cannot brake), choose as before.
  EXPECT_FALSE(maptr::control::braking_demand(turn_side(1, true)));
  EXPECT_FALSE(maptr::control::braking_demand(turn_side(0, false)));
  Level2Problem half = inner;
  half.live = 4;  // four agents left on the side: all of them
  EXPECT_EQ(exhaustive_level2(half).n_active, 4);
}

}  // namespace
