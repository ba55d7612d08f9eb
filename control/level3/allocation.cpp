#include "control/level3/allocation.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace maptr::control {

std::vector<uint8_t> allocate(const AllocationInput& in) {
  const std::size_t n = in.live.size();
  if (in.distance_m.size() != n)
    throw std::invalid_argument("allocate: distance_m and live differ in length");
  std::vector<std::size_t> cool, hot;
  for (std::size_t j = 0; j < n; ++j) {
    if (!in.live[j]) continue;
    const bool overheated = j < in.active_time_s.size() && in.active_time_s[j] >= in.thermal_limit_s;
    (overheated ? hot : cool).push_back(j);
  }
  auto by_distance = [&](std::size_t a, std::size_t b) {
    const double da = in.distance_m[a], db = in.distance_m[b];
    return da != db ? da < db : a < b;
  };
  std::sort(cool.begin(), cool.end(), by_distance);
  std::sort(hot.begin(), hot.end(), by_distance);
  cool.insert(cool.end(), hot.begin(), hot.end());
  std::vector<uint8_t> x(n, 0);
  const std::size_t want = static_cast<std::size_t>(std::max(0, in.n_active));
  for (std::size_t k = 0; k < std::min(want, cool.size()); ++k) x[cool[k]] = 1;
  return x;
}

double allocation_cost(const std::vector<double>& d, const std::vector<uint8_t>& x) {
  const double total = std::accumulate(d.begin(), d.end(), 0.0);
  const double d_ref = d.empty() ? 0.0 : 1.0 / d.size();
  double c = 0.0;
  for (std::size_t j = 0; j < d.size(); ++j)
    if (x[j]) c += (total > 0.0 ? d[j] / total : 0.0) - d_ref;
  return c;
}

}  // namespace maptr::control
