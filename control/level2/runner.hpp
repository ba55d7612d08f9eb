#pragma once
// Who solves a group's Level-2 decisions. The group core hands a runner the problem of tick k
// (start) and takes the outcome when the decision is due, at tick k + d (finish). A runner may
// solve at once (InlineLevel2Runner) or elsewhere (the group node's worker thread); finish()
// returns only a finished solve, so the outcome depends on the problem alone, never on when
// it was solved. The core calls finish() exactly once after each start(), before the next.
#include <memory>

#include "control/level2/problem.hpp"
#include "control/level2/solver.hpp"

namespace maptr::control {

/// One Level-2 decision: the solver's result and, if asked for, the oracle's choice.
struct Level2Outcome {
  Level2Result result;
  int oracle_n_active = -1;  ///< exhaustive_level2()'s N_a; -1 when the oracle did not run
};

/// Solves p with solver (warm start from its previous solve) and, if oracle, also exhaustively.
Level2Outcome solve_level2(Level2Solver& solver, const Level2Problem& p, bool oracle);

class Level2Runner {
 public:
  virtual ~Level2Runner() = default;
  /// Starts solving p (a copy is kept).
  virtual void start(const Level2Problem& p) = 0;
  /// The outcome of the last start(); waits for it if it is still being solved.
  virtual Level2Outcome finish() = 0;
};

/// Solves in start(), on the caller's thread.
class InlineLevel2Runner : public Level2Runner {
 public:
  explicit InlineLevel2Runner(bool oracle) : oracle_(oracle) {}
  void start(const Level2Problem& p) override { outcome_ = solve_level2(solver_, p, oracle_); }
  Level2Outcome finish() override { return outcome_; }

 private:
  bool oracle_;
  Level2Solver solver_;
  Level2Outcome outcome_;
};

}  // namespace maptr::control
