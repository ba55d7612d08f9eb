// maptr_level2_bench: solve time and oracle agreement of the Level-2 solver on the cruise
// problems of the `weights` and `voltages` experiments (16 agents, one side, straight line).
// One solver per problem family, reused and warm-started as in a group process; the speed
// wanders around the reference (as in cruise) from one decision to the next.
// Usage: maptr_level2_bench [DECISIONS_PER_FAMILY [WANDER [MAX_ITER [TOL]]]]
//        (defaults 200, 0.03 and the solver's Level2SolverConfig::max_iter and tol)
// WANDER: relative amplitude of the speed's wander around the reference (larger: more decisions
// in the braking and clamping regions, where J has several local maxima). MAX_ITER: Ipopt's
// iteration limit, to compare limits in one sitting. TOL: Ipopt's convergence tolerance, likewise.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "control/level2/problem.hpp"
#include "control/level2/solver.hpp"

namespace {

using maptr::control::exhaustive_level2;
using maptr::control::Level2Problem;
using maptr::control::Level2Solver;

struct Family {
  std::string name;
  double mass_kg, speed_mps, battery_V;
};

/// Default relative amplitude of the speed's wander around the reference.
constexpr double kDefaultWander = 0.03;

/// CPU time of the calling thread, ms (what the solve costs, whatever else the machine runs).
double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * (v.size() - 1) + 0.5)];
}

double sum_cpu(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

/// The command line: DECISIONS_PER_FAMILY, WANDER, MAX_ITER, TOL (each optional, in that order).
struct Args {
  int decisions = 200;
  double wander = kDefaultWander;
  maptr::control::Level2SolverConfig config;
};

/// A positive integer, or 0 when `text` is not one.
int positive_int(const char* text) {
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  return end != text && *end == '\0' && v >= 1 && v <= 1000000000 ? static_cast<int>(v) : 0;
}

/// The number `text` holds, whole; false when it holds something else.
bool whole_number(const char* text, double& out) {
  char* end = nullptr;
  out = std::strtod(text, &end);
  return end != text && *end == '\0';
}

/// Parses the command line; prints what is wrong and returns false on a bad argument.
bool parse_args(int argc, char** argv, Args& a) {
  if (argc > 1 && (a.decisions = positive_int(argv[1])) == 0) {
    std::fprintf(stderr, "maptr_level2_bench: DECISIONS_PER_FAMILY = %s: must be a positive integer\n", argv[1]);
    return false;
  }
  if (argc > 2 && !(whole_number(argv[2], a.wander) && a.wander >= 0.0 && a.wander < 1.0)) {
    std::fprintf(stderr, "maptr_level2_bench: WANDER = %s: must be a number in [0, 1)\n", argv[2]);
    return false;
  }
  if (argc > 3 && (a.config.max_iter = positive_int(argv[3])) == 0) {
    std::fprintf(stderr, "maptr_level2_bench: MAX_ITER = %s: must be a positive integer\n", argv[3]);
    return false;
  }
  if (argc > 4 && !(whole_number(argv[4], a.config.tol) && a.config.tol > 0.0 && a.config.tol < 1.0)) {
    std::fprintf(stderr, "maptr_level2_bench: TOL = %s: must be a number in (0, 1)\n", argv[4]);
    return false;
  }
  if (argc > 5) {
    std::fprintf(stderr, "maptr_level2_bench: %s: too many arguments\n", argv[5]);
    return false;
  }
  return true;
}

/// Decision i of family f: 16 agents, the side alternating, the speed wandering by `wander`.
Level2Problem problem(const Family& f, int i, double wander) {
  Level2Problem p;
  p.robot.agents = 16;
  p.robot.gross_mass_kg = f.mass_kg;
  p.side = i % 2;
  p.live = p.robot.per_side();
  p.n_other = 0.0;
  p.phidot_ref_L = p.phidot_ref_R = f.speed_mps / p.robot.wheel_radius_m;
  p.v_x = f.speed_mps * (1.0 + wander * std::sin(0.7 * i));
  p.battery_V = f.battery_V;
  p.validate();
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (!parse_args(argc, argv, args)) return 2;
  const int decisions = args.decisions;
  const double wander = args.wander;
  const maptr::control::Level2SolverConfig& config = args.config;
  const std::vector<Family> families = {
      {"weights 13.2 kg", 13.2, 10.0, 23.4}, {"weights 23.2 kg", 23.2, 10.0, 23.4},
      {"weights 33.2 kg", 33.2, 10.0, 23.4}, {"voltages 12 V", 14.4, 8.0, 12.0},
      {"voltages 16 V", 14.4, 8.0, 16.0},    {"voltages 20 V", 14.4, 8.0, 20.0},
      {"voltages 23.4 V", 14.4, 8.0, 23.4}};
  std::vector<double> all, all_cpu;
  int differ = 0, total = 0, failed = 0;
  long iterations = 0;
  double failed_cpu = 0.0;
  for (const Family& f : families) {
    Level2Solver solver(config);
    std::vector<double> times, cpu;
    for (int i = 0; i < decisions; ++i) {
      const Level2Problem p = problem(f, i, wander);
      const double c0 = thread_cpu_ms();
      const auto r = solver.solve(p);
      cpu.push_back(thread_cpu_ms() - c0);
      if (r.ipopt_status < 0) {  // Ipopt did not converge: the integer choice compared every n
        ++failed;
        failed_cpu += cpu.back();
      }
      times.push_back(r.solve_time_ms);
      iterations += r.iterations;
      const auto oracle = exhaustive_level2(p);
      if (r.n_active != oracle.n_active) {
        ++differ;
        std::printf(
            "  differ: %s v %.3f side %d: solver %d (relaxed %.4f, status %d, J %.7f), oracle %d (J %.7f)\n",
            f.name.c_str(), p.v_x, p.side, r.n_active, r.n_relaxed, r.ipopt_status, r.objective,
            oracle.n_active, oracle.objective);
      }
      ++total;
    }
    all.insert(all.end(), times.begin(), times.end());
    all_cpu.insert(all_cpu.end(), cpu.begin(), cpu.end());
    std::printf("%-16s wall median %7.3f ms  p95 %7.3f ms  max %7.3f ms | cpu median %7.3f ms\n",
                f.name.c_str(), percentile(times, 0.5), percentile(times, 0.95), percentile(times, 1.0),
                percentile(cpu, 0.5));
  }
  std::printf(
      "all %d decisions (max_iter %d, tol %g): wall median %.3f ms, p95 %.3f ms; cpu median %.3f ms, max %.3f ms, "
      "total %.0f ms; %.1f Ipopt iterations a solve; not converged %d (%.0f ms cpu); solver != oracle in %d\n",
      total, config.max_iter, config.tol, percentile(all, 0.5), percentile(all, 0.95), percentile(all_cpu, 0.5),
      percentile(all_cpu, 1.0), sum_cpu(all_cpu), static_cast<double>(iterations) / total, failed, failed_cpu,
      differ);
  return 0;
}
