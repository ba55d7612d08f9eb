#include "control/level2/solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <coin/IpIpoptApplication.hpp>
#include <coin/IpSolveStatistics.hpp>
#include <coin/IpTNLP.hpp>
#include <vector>

#include "control/level2/runner.hpp"

namespace maptr::control {
namespace {

using Ipopt::Index;
using Ipopt::Number;

constexpr double kFdStep = 1e-3;   ///< agents, step of the objective's three-point stencil
constexpr double kGFdStep = 1e-5;  ///< agents, central-difference step of the closed-form constraint
/// Constraint lower bound that Ipopt reads as none (below its nlp_lower_bound_inf, -1e19).
constexpr double kNoLowerBound = -2e19;
constexpr double kIntegerWiden =
    1e-3;  ///< agents: a relaxed n* this close to an integer brings in both neighbours
/// Integer candidates beyond floor and ceil of n*, on each side: J is not unimodal everywhere
/// (flat where the speed loop brakes, kinked where the voltage clamps), and n* can sit in the
/// basin next to the best integer.
constexpr int kNeighbours = 1;
/// Ipopt's initial barrier parameter for a cold start (its default) and for a start from the
/// previous solution and its multipliers (already near the central path).
constexpr double kMuInitCold = 0.1;
constexpr double kMuInitWarm = 1e-2;
/// How far (relative) a warm start's point and multipliers are pushed off their bounds.
constexpr double kWarmBoundPush = 1e-6;
/// MUMPS workspace above its estimate, percent (the system is 3 x 3; Ipopt's default 1000 costs
/// an allocation per factorization; MUMPS enlarges it itself if ever short).
constexpr int kMumpsMemPercent = 5;

/// A primal-dual point of the relaxed NLP: n and the multipliers of its bounds and constraint.
struct Level2Iterate {
  double x = 0.0;        ///< agents
  double z_lower = 0.0;  ///< multiplier of n >= 1
  double z_upper = 0.0;  ///< multiplier of n <= live
  double lambda = 0.0;   ///< multiplier of feasibility_voltage(n) <= V_B
};

/// The relaxed Level-2 NLP: one variable n, one constraint g(n) = feasibility_voltage(n).
/// The objective, its slope and curvature at a point come from one stencil of three rollouts
/// (n - h, n, n + h), computed once per point whatever Ipopt asks there; a trial point of the
/// line search costs one rollout. One instance serves every solve of a Level2Solver (Ipopt
/// re-optimises the same NLP); reset() sets the next problem and start.
class Level2Nlp : public Ipopt::TNLP {
 public:
  explicit Level2Nlp(bool fd_hessian) : fd_hessian_(fd_hessian) {}

  /// The next solve: problem p from start (with_multipliers: start's multipliers too).
  void reset(const Level2Problem& p, const Level2Iterate& start, bool with_multipliers) {
    p_ = p;
    start_ = start;
    with_multipliers_ = with_multipliers;
    solution_ = start;
    solved_ = false;
    has_x_ = false;
    has_stencil_ = false;
  }

  /// The last solve's point (its start if Ipopt gave none) and whether Ipopt converged there.
  const Level2Iterate& solution() const { return solution_; }
  bool solved() const { return solved_; }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = 1;
    m = 1;
    nnz_jac_g = 1;
    nnz_h_lag = fd_hessian_ ? 1 : 0;
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index, Number* x_l, Number* x_u, Index, Number* g_l, Number* g_u) override {
    x_l[0] = 1.0;
    x_u[0] = static_cast<double>(p_.live);
    g_l[0] = kNoLowerBound;
    g_u[0] = p_.battery_V;
    return true;
  }

  bool get_starting_point(Index, bool init_x, Number* x, bool init_z, Number* z_l, Number* z_u, Index,
                          bool init_lambda, Number* lambda) override {
    if ((init_z || init_lambda) && !with_multipliers_) return false;
    if (init_x) x[0] = start_.x;
    if (init_z) {
      z_l[0] = start_.z_lower;
      z_u[0] = start_.z_upper;
    }
    if (init_lambda) lambda[0] = start_.lambda;
    return true;
  }

  bool eval_f(Index, const Number* x, bool, Number& obj) override {
    obj = -value(x[0]);
    return std::isfinite(obj);
  }

  bool eval_grad_f(Index, const Number* x, bool, Number* grad) override {
    stencil(x[0]);
    grad[0] = -(f_plus_ - f_minus_) / (2.0 * kFdStep);
    return std::isfinite(grad[0]);
  }

  bool eval_g(Index, const Number* x, bool, Index, Number* g) override {
    g[0] = feasibility_voltage(p_, x[0]);
    return std::isfinite(g[0]);
  }

  bool eval_jac_g(Index, const Number* x, bool, Index, Index, Index* i_row, Index* j_col,
                  Number* values) override {
    if (values == nullptr) {
      i_row[0] = 0;
      j_col[0] = 0;
      return true;
    }
    const double h = kGFdStep;
    values[0] = (feasibility_voltage(p_, x[0] + h) - feasibility_voltage(p_, x[0] - h)) / (2.0 * h);
    return std::isfinite(values[0]);
  }

  /// The 1x1 Hessian of the Lagrangian, obj_factor f'' + lambda g'', by second differences.
  bool eval_h(Index, const Number* x, bool, Number obj_factor, Index, const Number* lambda, bool, Index,
              Index* i_row, Index* j_col, Number* values) override {
    if (!fd_hessian_) return false;
    if (values == nullptr) {
      i_row[0] = 0;
      j_col[0] = 0;
      return true;
    }
    const double x0 = x[0], h = kFdStep;
    stencil(x0);
    const double j2 = (f_plus_ - 2.0 * f_x_ + f_minus_) / (h * h);
    const double g2 = (feasibility_voltage(p_, x0 + h) - 2.0 * feasibility_voltage(p_, x0) +
                       feasibility_voltage(p_, x0 - h)) /
                      (h * h);
    values[0] = -obj_factor * j2 + lambda[0] * g2;
    return std::isfinite(values[0]);
  }

  void finalize_solution(Ipopt::SolverReturn status, Index, const Number* x, const Number* z_l,
                         const Number* z_u, Index, const Number*, const Number* lambda, Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    if (x != nullptr && std::isfinite(x[0])) solution_.x = x[0];
    solved_ = status == Ipopt::SUCCESS && z_l != nullptr && z_u != nullptr && lambda != nullptr;
    if (solved_) {
      solution_.z_lower = z_l[0];
      solution_.z_upper = z_u[0];
      solution_.lambda = lambda[0];
    }
  }

 private:
  /// The objective at x (one rollout, cached for the last point).
  double value(double x) {
    if (!has_x_ || x != at_x_) {
      at_x_ = x;
      has_x_ = true;
      has_stencil_ = false;
      f_x_ = level2_objective(p_, x);
    }
    return f_x_;
  }
  /// The objective at x - h and x + h beside value(x) (two more rollouts, once per point).
  void stencil(double x) {
    value(x);
    if (has_stencil_) return;
    f_minus_ = level2_objective(p_, x - kFdStep);
    f_plus_ = level2_objective(p_, x + kFdStep);
    has_stencil_ = true;
  }

  Level2Problem p_;
  Level2Iterate start_, solution_;
  bool with_multipliers_ = false;
  bool solved_ = false;
  bool fd_hessian_;
  bool has_x_ = false, has_stencil_ = false;
  double at_x_ = 0.0, f_x_ = 0.0, f_minus_ = 0.0, f_plus_ = 0.0;
};

/// The integers the choice compares: floor - kNeighbours .. ceil + kNeighbours of the relaxed
/// n*, clipped to [1, live], and live itself (when the body is above its reference the speed
/// loop brakes, J is flat near 0 for small n and Ipopt can stop at n = 1 below a better
/// n = live). Ipopt did not converge (its n* says nothing): every n in [1, live].
std::vector<int> integer_candidates(double x, int live, bool converged) {
  const int k_lo = converged ? std::max(1, static_cast<int>(std::floor(x - kIntegerWiden)) - kNeighbours) : 1;
  const int k_hi =
      converged ? std::min(live, static_cast<int>(std::ceil(x + kIntegerWiden)) + kNeighbours) : live;
  std::vector<int> candidates;
  for (int k = k_lo; k <= k_hi; ++k) candidates.push_back(k);
  if (k_hi < live) candidates.push_back(live);
  return candidates;
}

/// Among the feasible candidates, the largest objective (ties to the smaller n, as the oracle)
/// into res.n_active and res.objective; false if none is feasible.
bool choose_integer(const Level2Problem& p, const std::vector<int>& candidates, Level2Result& res) {
  bool found = false;
  for (int k : candidates) {
    if (!level2_feasible(p, k)) continue;
    const double j = level2_objective(p, k);
    if (!found || j > res.objective) {  // strict: ties keep the smaller n
      res.n_active = k;
      res.objective = j;
      found = true;
    }
  }
  return found;
}

}  // namespace

void Level2SolverConfig::validate() const {
  if (!(std::isfinite(tol) && tol > 0.0))
    throw model::ParamError("level2_solver.tol = " + std::to_string(tol) + ": must be positive");
  if (max_iter < 1)
    throw model::ParamError("level2_solver.max_iter = " + std::to_string(max_iter) + ": must be >= 1");
}

struct Level2Solver::Impl {
  Level2SolverConfig config;
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app;
  Ipopt::SmartPtr<Level2Nlp> nlp;  ///< one NLP for every solve
  bool init_ok = false;
  bool built = false;  ///< Ipopt's algorithm objects exist (an OptimizeTNLP completed)
  bool has_warm = false;
  bool warm_multipliers = false;  ///< warm holds the multipliers of a converged solve
  Level2Iterate warm;             ///< previous relaxed solution (agents) and its multipliers

  /// Runs Ipopt on nlp from start: builds its algorithm objects once, then re-optimises with
  /// them; a start with multipliers is a warm start near the central path.
  int optimize(bool with_multipliers) {
    Ipopt::SmartPtr<Ipopt::OptionsList> o = app->Options();
    o->SetStringValue("warm_start_init_point", with_multipliers ? "yes" : "no");
    o->SetNumericValue("mu_init", with_multipliers ? kMuInitWarm : kMuInitCold);
    if (built) {
      o->SetStringValue("warm_start_same_structure", "yes");  // keeps the NLP's spaces
      try {
        return static_cast<int>(app->ReOptimizeTNLP(nlp));
      } catch (const Ipopt::IpoptException&) {
        built = false;  // no algorithm objects to re-use: build them again
      }
    }
    o->SetStringValue("warm_start_same_structure", "no");
    const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(nlp);
    built = status != Ipopt::Invalid_Option && status != Ipopt::Unrecoverable_Exception &&
            status != Ipopt::NonIpopt_Exception_Thrown && status != Ipopt::Insufficient_Memory;
    return static_cast<int>(status);
  }
};

Level2Solver::Level2Solver(Level2SolverConfig config) : impl_(std::make_unique<Impl>()) {
  config.validate();
  impl_->config = config;
  impl_->app = IpoptApplicationFactory();
  Ipopt::SmartPtr<Ipopt::OptionsList> o = impl_->app->Options();
  o->SetIntegerValue("print_level", 0);
  o->SetStringValue("sb", "yes");  // no banner
  o->SetNumericValue("tol", config.tol);
  o->SetStringValue("hessian_approximation", config.fd_hessian ? "exact" : "limited-memory");
  o->SetIntegerValue("max_iter", config.max_iter);
  o->SetStringValue("mu_strategy", "monotone");  // cheaper than adaptive here (BENCHMARKS.md)
  // Per-solve costs (docs/bench/HISTORY.md, "Solve time after re-using Ipopt"): no gradient
  // scaling (|grad| stays far below its threshold), no least-squares constraint multipliers at a
  // cold start, no forced iterative refinement, a small MUMPS workspace; a warm start's point and
  // multipliers stay where they were.
  o->SetStringValue("nlp_scaling_method", "none");
  o->SetNumericValue("constr_mult_init_max", 0.0);
  o->SetIntegerValue("min_refinement_steps", 0);
  o->SetIntegerValue("mumps_mem_percent", kMumpsMemPercent);
  o->SetNumericValue("warm_start_bound_push", kWarmBoundPush);
  o->SetNumericValue("warm_start_mult_bound_push", kWarmBoundPush);
  impl_->init_ok = impl_->app->Initialize("") == Ipopt::Solve_Succeeded;  // "": no ipopt.opt file
  impl_->nlp = new Level2Nlp(config.fd_hessian);
}

Level2Solver::~Level2Solver() = default;

Level2Result Level2Solver::solve(const Level2Problem& p) {
  const auto t0 = std::chrono::steady_clock::now();
  Level2Result res;
  const int live = p.live;

  if (live <= 1 || braking_demand(p)) {  // nothing to choose, or every live agent brakes
    res.n_active = std::max(live, 0);
    res.n_relaxed = res.n_active;
    res.feasible = live >= 1 && level2_feasible(p, res.n_active);
    res.objective = live >= 1 ? level2_objective(p, res.n_active) : 0.0;
    res.ipopt_status = kLevel2NotSolved;
  } else {
    const double lo = 1.0, hi = live;
    Level2Iterate start = impl_->has_warm ? impl_->warm : Level2Iterate{0.5 * (lo + hi)};
    start.x = std::clamp(start.x, lo, hi);
    const bool with_multipliers = impl_->has_warm && impl_->warm_multipliers;
    double x = start.x;
    bool solved = false;
    if (impl_->init_ok) {
      impl_->nlp->reset(p, start, with_multipliers);
      res.ipopt_status = impl_->optimize(with_multipliers);
      x = impl_->nlp->solution().x;
      solved = impl_->nlp->solved();
      Ipopt::SmartPtr<Ipopt::SolveStatistics> stats = impl_->app->Statistics();
      if (Ipopt::IsValid(stats)) res.iterations = stats->IterationCount();
    } else {
      res.ipopt_status = kLevel2InitFailed;
    }
    x = std::clamp(x, lo, hi);
    res.n_relaxed = x;

    const bool converged = res.ipopt_status >= 0 && res.ipopt_status < kLevel2NotSolved;
    if (choose_integer(p, integer_candidates(x, live, converged), res)) {
      res.feasible = true;
      impl_->warm = impl_->nlp->solution();
      impl_->warm.x = x;
      impl_->warm_multipliers = solved;
      impl_->has_warm = true;
    } else {
      res.n_active = live;
      res.feasible = level2_feasible(p, live);
      res.objective = level2_objective(p, live);
    }
  }

  res.solve_time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

Level2Outcome solve_level2(Level2Solver& solver, const Level2Problem& p, bool oracle) {
  Level2Outcome o;
  o.result = solver.solve(p);
  if (oracle) o.oracle_n_active = exhaustive_level2(p).n_active;
  return o;
}

}  // namespace maptr::control
