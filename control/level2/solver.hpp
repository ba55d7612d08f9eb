#pragma once
// Level-2 solver of a group: Ipopt on the relaxed problem of level2/problem.hpp, then the
// integer choice.
//   minimise   -(J(n) - c n)                   J = horizon_efficiency(problem, n), in [0, H]
//   subject to 1 <= n <= live                  (n real: the relaxed number of active agents)
//              feasibility_voltage(n) <= V_B   [V]
// Derivatives from a three-point stencil of rollouts per point. Warm start from the previous
// relaxed solution and, if Ipopt converged there, its multipliers (a smaller initial barrier
// parameter); the first solve starts at the middle of [1, live]. Integer choice: floor - 1 to
// ceil + 1 of the relaxed n* (widened by kIntegerWiden), clipped to [1, live], and live itself
// (J can be flat near 0 for small n while the body brakes), or every n in [1, live] when Ipopt
// did not converge (a failed status; its n* says nothing), each kept if feasible; the largest
// objective wins, ties to the smaller n (as the oracle exhaustive_level2()). None feasible: every
// live agent runs (n_active = live). Deterministic; solve_time_ms is diagnostics only.
// One Ipopt application and one NLP per instance, built at the first solve and re-optimised
// after; not thread-safe (one solver per group thread).
#include <memory>

#include "control/level2/problem.hpp"

namespace maptr::control {

/// ipopt_status when Ipopt was not called (live <= 1, or a braking demand: nothing to choose).
constexpr int kLevel2NotSolved = 100;
/// ipopt_status when Ipopt could not be initialised (invalid option; should not happen).
constexpr int kLevel2InitFailed = 101;

struct Level2Result {
  int n_active = 0;                     ///< chosen N_a (integer, in [1, live]; 0 only when live = 0)
  double n_relaxed = 0.0;               ///< Ipopt's continuous solution n*
  bool feasible = false;                ///< false: even every live agent cannot hold the reference
  int ipopt_status = kLevel2NotSolved;  ///< Ipopt ApplicationReturnStatus, or kLevel2* above
  double solve_time_ms = 0.0;           ///< ms, wall clock of solve() (diagnostics only)
  int iterations = 0;                   ///< Ipopt iterations
  double objective = 0.0;               ///< level2_objective(n_active): J - c n_active
};

struct Level2SolverConfig {
  bool fd_hessian = true;  ///< true: exact Hessian by finite differences; false: limited-memory
  double tol = 1e-6;       ///< Ipopt tol (scaled KKT error)
  /// Ipopt iterations. A solve that converges takes about 5; one still unconverged at 30 sits
  /// where J(n) has kinks (speed above the reference: the loop brakes, the voltage clamps at 0)
  /// and failed at 100 as well in maptr_level2_bench, and an unconverged solve's integer choice
  /// compares every n anyway. 100 changed no decision there and made such solves cost up to
  /// 145 ms instead of 23 ms (docs/bench/HISTORY.md, "Ipopt's iteration limit").
  int max_iter = 30;
  void validate() const;   ///< throws model::ParamError naming the field
};

class Level2Solver {
 public:
  explicit Level2Solver(Level2SolverConfig config = {});
  ~Level2Solver();
  Level2Solver(const Level2Solver&) = delete;
  Level2Solver& operator=(const Level2Solver&) = delete;

  /// Solves one Level-2 decision. The problem must be valid (Level2Problem::validate()).
  Level2Result solve(const Level2Problem& problem);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace maptr::control
