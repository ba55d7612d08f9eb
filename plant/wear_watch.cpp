#include "plant/wear_watch.hpp"

#include <algorithm>

namespace maptr::plant {

void WearWatch::on_status(int side, const std::vector<double>& wear_m, double t_s) {
  Side& s = sides_[side];
  bool dropped = false;
  for (std::size_t j = 0; j < std::min(wear_m.size(), s.wear_m.size()); ++j) {
    const double drop = s.wear_m[j] - wear_m[j];
    if (drop <= tolerance_m_) continue;
    dropped = true;
    s.largest_drop_m = std::max(s.largest_drop_m, drop);
  }
  if (dropped) {
    ++s.regressions;
    if (s.first_regression_s < 0.0) s.first_regression_s = t_s;
  }
  s.wear_m = wear_m;
}

nlohmann::json WearWatch::json() const {
  nlohmann::json j = nlohmann::json::object();
  for (int side = 0; side < 2; ++side) {
    const Side& s = sides_[side];
    j[side == 0 ? "L" : "R"] = {
        {"wear_m", s.wear_m},
        {"regressions", s.regressions},
        {"largest_drop_m", s.largest_drop_m},
        {"first_regression_s",
         s.first_regression_s < 0.0 ? nlohmann::json() : nlohmann::json(s.first_regression_s)}};
  }
  return j;
}

}  // namespace maptr::plant
