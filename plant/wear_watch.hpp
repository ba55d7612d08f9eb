#pragma once
// The groups' wear ledgers as the plant sees them in their statuses: for every agent j of a
// side, D_j [m] (the distance it drove while active) must never decrease from one status to
// the next, across restarts and pauses of the group. A drop larger than a tolerance [m] is a
// regression; the report gives the last ledger seen and every regression's count and size.
#include <nlohmann/json.hpp>
#include <vector>

namespace maptr::plant {

class WearWatch {
 public:
  /// tolerance_m: a drop up to this size is rounding, not a regression, m.
  explicit WearWatch(double tolerance_m = kToleranceM) : tolerance_m_(tolerance_m) {}

  /// A group status of side `side` (0 = L, 1 = R) at simulated time t_s carried `wear_m`.
  void on_status(int side, const std::vector<double>& wear_m, double t_s);

  int regressions(int side) const { return sides_[side].regressions; }
  /// {"L": {wear_m, regressions, largest_drop_m, first_regression_s}, "R": {...}}
  nlohmann::json json() const;

  static constexpr double kToleranceM = 1e-9;

 private:
  struct Side {
    std::vector<double> wear_m;
    int regressions = 0;
    double largest_drop_m = 0.0;
    double first_regression_s = -1.0;
  };
  double tolerance_m_;
  Side sides_[2];
};

}  // namespace maptr::plant
