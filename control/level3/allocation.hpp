#pragma once
// Level-3 online task allocation (paper eq. "online"):
//   min (D - D_ref)^T x   s.t.  sum x = N_a,  x in {0,1}^{N_i},  x_j = 0 for failed agents
// with D_j the distance agent j drove while active, normalised to sum 1, D_ref = 1/N_i.
//
// Why taking the N_a smallest entries is exact: the objective is sum_{j in S} c_j over the
// chosen set S with |S| = N_a, c_j = D_j - D_ref. For any feasible S that misses some j among
// the N_a smallest c and contains some k outside them, c_j <= c_k, so swapping k for j never
// increases the sum. Repeating the swap reaches the set of the N_a smallest without ever
// increasing the objective, so that set is optimal (ties broken by index, which makes the
// answer deterministic). Normalisation and D_ref shift every c_j by the same amount and scale
// them by the same positive factor, so they do not change the argmin: only the order of D matters.
//
// Thermal limit: agents whose continuous active time reached the limit are taken only when
// there are not enough others (then the ones with the smallest D among them).
#include <cstdint>
#include <vector>

namespace maptr::control {

struct AllocationInput {
  std::vector<double> distance_m;     ///< D_j, m driven while active (un-normalised)
  std::vector<uint8_t> live;          ///< 1 = agent alive
  std::vector<double> active_time_s;  ///< continuous active time so far, s (may be empty)
  double thermal_limit_s = 600.0;     ///< T_max of continuous operation, s
  int n_active = 0;                   ///< N_a wanted
};

/// Returns the activation mask (1 = active). Takes min(n_active, live count) agents.
std::vector<uint8_t> allocate(const AllocationInput& in);

/// Objective (D - D_ref)^T x with D normalised to sum 1 (all-zero D gives D = 0).
double allocation_cost(const std::vector<double>& distance_m, const std::vector<uint8_t>& x);

}  // namespace maptr::control
