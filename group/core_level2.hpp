#pragma once
// Level-2 solver of a group (DESIGN "Control levels", Level 2): Ipopt on the relaxed problem
// of model/level2.hpp, then the integer choice.
//
//   minimise   -(J(n) - c n)              J = horizon_efficiency(problem, n)   (in [0, H]),
//                                         c = problem.agent_cost (tie-break, see level2.hpp)
//   subject to 1 <= n <= live             (n real: the relaxed number of active agents)
//              feasibility_voltage(n) <= battery_V                              [V]
//
// Gradient and constraint Jacobian by central finite differences (step 1e-5 agents); tol 1e-6;
// no output (print_level 0, sb yes, no options file); monotone barrier update.
// Hessian: by default the exact 1x1 Hessian of the Lagrangian by central second differences
// (step 1e-3 agents: 3 rollouts). Limited-memory BFGS (Level2SolverConfig::fd_hessian = false)
// gives the same answers but is about 1.5x slower here: Ipopt's low-rank augmented-system
// solver makes several MUMPS solves per iteration, and each MUMPS 5.5 call has a fixed cost
// larger than this whole 1-variable step. Both are tested against the oracle.
// The start point is the previous relaxed solution of this solver (warm start), clipped to
// [1, live]; the first solve starts at the middle of [1, live].
// Integer choice: the integers next to the relaxed solution n* - floor and ceil, widened by
// 1e-3 agent so that a solution a hair beside an integer (within the solver tolerance) still
// brings in both neighbours - clipped to [1, live] and kept only if feasible; the one with the
// largest objective wins (ties: the smaller n, as in the oracle exhaustive_level2()). If none is
// feasible (Ipopt reports the problem infeasible, or its point is off), the group runs every
// live agent: n_active = live, feasible = level2_feasible(live) (false when the load is above
// what all live agents can give).
//
// One Ipopt application per solver instance (no singleton). Not thread-safe: one solver per
// group thread. solve_time_ms is wall-clock diagnostics (std::chrono::steady_clock) only; it
// never influences the result, which is deterministic.
#include <memory>

#include "model/level2.hpp"

namespace maptr::group {

/// ipopt_status when Ipopt was not called (live <= 1: nothing to choose).
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
  int max_iter = 100;      ///< Ipopt iterations
  void validate() const;   ///< throws model::ParamError naming the field
};

class Level2Solver {
 public:
  explicit Level2Solver(Level2SolverConfig config = {});
  ~Level2Solver();
  Level2Solver(const Level2Solver&) = delete;
  Level2Solver& operator=(const Level2Solver&) = delete;

  /// Solves one Level-2 decision. The problem must be valid (Level2Problem::validate()).
  Level2Result solve(const model::Level2Problem& problem);

  /// Forget the warm start (e.g. after a scenario change).
  void reset_warm_start();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace maptr::group
