// Level-3 allocation (control/level3/allocation.hpp) against brute force over every subset.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "control/level3/allocation.hpp"

namespace {

using maptr::control::AllocationInput;
using maptr::control::allocate;
using maptr::control::allocation_cost;

int count(const std::vector<uint8_t>& x) { return static_cast<int>(std::count(x.begin(), x.end(), 1)); }

struct Best {
  double cost = std::numeric_limits<double>::infinity();
  int hot = std::numeric_limits<int>::max();  // number of over-temperature agents chosen
};

// Brute force over all 2^n masks: among masks of min(n_active, live) live agents, the lexicographic
// minimum of (number of hot agents, cost). The cost is evaluated independently of allocation_cost:
// sum over chosen j of D_j / sum(D) - 1/n.
Best brute_force(const AllocationInput& in) {
  const int n = static_cast<int>(in.live.size());
  const int live = count(in.live);
  const int k = std::min(std::max(in.n_active, 0), live);
  double total = 0.0;
  for (double d : in.distance_m) total += d;
  Best best;
  for (uint32_t mask = 0; mask < (1u << n); ++mask) {
    if (__builtin_popcount(mask) != k) continue;
    bool ok = true;
    int hot = 0;
    double cost = 0.0;
    for (int j = 0; j < n && ok; ++j) {
      if (!(mask >> j & 1u)) continue;
      if (!in.live[j]) ok = false;
      if (j < static_cast<int>(in.active_time_s.size()) && in.active_time_s[j] >= in.thermal_limit_s) ++hot;
      cost += (total > 0.0 ? in.distance_m[j] / total : 0.0) - 1.0 / n;
    }
    if (!ok) continue;
    if (hot < best.hot || (hot == best.hot && cost < best.cost)) best = {cost, hot};
  }
  return best;
}

int hot_count(const AllocationInput& in, const std::vector<uint8_t>& x) {
  int h = 0;
  for (std::size_t j = 0; j < x.size(); ++j)
    if (x[j] && j < in.active_time_s.size() && in.active_time_s[j] >= in.thermal_limit_s) ++h;
  return h;
}

void check_against_brute_force(const AllocationInput& in, double* worst) {
  const std::vector<uint8_t> x = allocate(in);
  ASSERT_EQ(x.size(), in.live.size());
  const int live = count(in.live);
  EXPECT_EQ(count(x), std::min(std::max(in.n_active, 0), live));
  for (std::size_t j = 0; j < x.size(); ++j) {
    if (!in.live[j]) {
      EXPECT_EQ(x[j], 0) << "failed agent " << j << " chosen";
    }
  }
  const Best b = brute_force(in);
  EXPECT_EQ(hot_count(in, x), b.hot);
  // Objective equal to the brute-force optimum; 1e-12 absolute (costs are sums of <= 12 terms of order 1).
  const double c = allocation_cost(in.distance_m, x);
  EXPECT_NEAR(c, b.cost, 1e-12);
  *worst = std::max(*worst, std::fabs(c - b.cost));
}

TEST(Allocation, MatchesBruteForceOnRandomInstances) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> dist(0.0, 500.0);
  std::bernoulli_distribution alive(0.8);
  double worst = 0.0;
  for (int trial = 0; trial < 600; ++trial) {
    const int n = 1 + trial % 12;
    AllocationInput in;
    in.distance_m.resize(n);
    in.live.resize(n);
    const bool with_ties = trial % 3 == 0;
    for (int j = 0; j < n; ++j) {
      in.distance_m[j] = with_ties ? std::floor(dist(rng) / 100.0) * 100.0 : dist(rng);  // ties: few values
      in.live[j] = alive(rng);
    }
    in.n_active = std::uniform_int_distribution<int>(0, n + 1)(rng);
    check_against_brute_force(in, &worst);
  }
  const std::string w = [&] {
    std::ostringstream os;
    os << std::setprecision(3) << std::scientific << worst;
    return os.str();
  }();
  RecordProperty("allocation_max_cost_diff_vs_brute_force", w);
}

TEST(Allocation, ThermalLimitAgainstBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> dist(0.0, 500.0), on_time(0.0, 900.0);
  std::bernoulli_distribution alive(0.85);
  double worst = 0.0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 1 + trial % 12;
    AllocationInput in;
    in.thermal_limit_s = 600.0;
    for (int j = 0; j < n; ++j) {
      in.distance_m.push_back(dist(rng));
      in.live.push_back(alive(rng));
      in.active_time_s.push_back(on_time(rng));  // about a third are over the limit
    }
    in.n_active = std::uniform_int_distribution<int>(0, n)(rng);
    check_against_brute_force(in, &worst);
  }
}

TEST(Allocation, SmallestDistancesWinAndFailedAgentsAreNeverChosen) {
  AllocationInput in;
  in.distance_m = {50.0, 10.0, 40.0, 0.0, 30.0, 20.0};
  in.live = {1, 1, 1, 0, 1, 1};  // agent 3 has the smallest D but is dead
  in.n_active = 3;
  // Hand answer: live agents sorted by D are 1 (10), 5 (20), 4 (30).
  EXPECT_EQ(allocate(in), (std::vector<uint8_t>{0, 1, 0, 0, 1, 1}));
  // Hand cost: D sums to 150, D_ref = 1/6: (10 + 20 + 30)/150 - 3/6 = 0.4 - 0.5 = -0.1.
  EXPECT_NEAR(allocation_cost(in.distance_m, allocate(in)), -0.1, 1e-15);
  // Asking for more than are alive gives every live agent, never the dead one.
  in.n_active = 6;
  EXPECT_EQ(allocate(in), (std::vector<uint8_t>{1, 1, 1, 0, 1, 1}));
  in.n_active = 0;
  EXPECT_EQ(count(allocate(in)), 0);
  in.n_active = -2;
  EXPECT_EQ(count(allocate(in)), 0);
  // Everyone dead: nobody chosen.
  in.live = {0, 0, 0, 0, 0, 0};
  in.n_active = 3;
  EXPECT_EQ(count(allocate(in)), 0);
}

TEST(Allocation, ThermalLimitRespectedWhenPossible) {
  AllocationInput in;
  in.distance_m = {0.0, 10.0, 20.0, 30.0, 40.0};
  in.live = {1, 1, 1, 1, 1};
  in.active_time_s = {600.0, 700.0, 0.0, 100.0, 599.9};  // 0 and 1 reached T_max = 600 s
  in.thermal_limit_s = 600.0;
  in.n_active = 3;
  // Enough cool agents (2, 3, 4): they are taken although 0 and 1 drove less.
  EXPECT_EQ(allocate(in), (std::vector<uint8_t>{0, 0, 1, 1, 1}));
  // Not enough: all cool ones plus the hot one with the smallest D (agent 0).
  in.n_active = 4;
  EXPECT_EQ(allocate(in), (std::vector<uint8_t>{1, 0, 1, 1, 1}));
}

TEST(Allocation, TiesAreBrokenByIndexDeterministically) {
  AllocationInput in;
  in.distance_m = {5.0, 5.0, 5.0, 5.0, 5.0, 5.0};
  in.live = {1, 0, 1, 1, 1, 1};
  in.n_active = 3;
  const std::vector<uint8_t> first = allocate(in);
  EXPECT_EQ(first, (std::vector<uint8_t>{1, 0, 1, 1, 0, 0}));
  for (int k = 0; k < 10; ++k) EXPECT_EQ(allocate(in), first);
  // All-zero D (start of a run): D normalises to 0, cost = -N_a / N_i = -0.5; lowest indices chosen.
  in.distance_m.assign(6, 0.0);
  EXPECT_EQ(allocate(in), first);
  EXPECT_NEAR(allocation_cost(in.distance_m, first), -0.5, 1e-15);
}

TEST(Allocation, NormalisationDoesNotChangeTheChoice) {
  // Scaling D by a positive factor (metres vs normalised) leaves the argmin unchanged.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> dist(0.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    AllocationInput a;
    for (int j = 0; j < 10; ++j) {
      a.distance_m.push_back(dist(rng));
      a.live.push_back(1);
    }
    a.n_active = 1 + trial % 10;
    AllocationInput b = a;
    for (double& d : b.distance_m) d *= 3700.0;
    EXPECT_EQ(allocate(a), allocate(b));
  }
}

}  // namespace
