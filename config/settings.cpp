#include "config/settings.hpp"

#include <charconv>

#include "control/central_core.hpp"
#include "control/group_core.hpp"
#include "control/level2/solver.hpp"

namespace maptr::config {

std::string setting_value(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, r.ptr);
}
std::string setting_value(int v) { return std::to_string(v); }
std::string setting_value(bool v) { return v ? "true" : "false"; }
std::string setting_value(std::chrono::milliseconds v) { return std::to_string(v.count()); }

std::vector<Setting> core_settings() {
  const control::GroupConfig g;
  const control::Level2SolverConfig l2;
  const control::CentralConfig c;
  return {
      {"central.min_lookahead_m", setting_value(c.min_lookahead_m), "m",
       "the path follower's shortest look-ahead L_min (L = max(4 |v| / K, L_min))"},
      {"central.search_ahead_m", setting_value(c.search_ahead_m), "m",
       "the path's nearest point is sought up to the reference's arc length + this"},
      {"group.cruise_enter", setting_value(g.cruise_enter), "1",
       "relative speed error at or below which a side is in cruise (Level 2 decides only then)"},
      {"group.cruise_leave", setting_value(g.cruise_leave), "1",
       "relative speed error above which cruise ends"},
      {"level2.tol", setting_value(l2.tol), "1", "Ipopt's tolerance (scaled KKT error)"},
      {"level2.max_iter", setting_value(l2.max_iter), "",
       "Ipopt's iterations; an unconverged solve's integer choice still compares every count"},
      {"level2.fd_hessian", setting_value(l2.fd_hessian), "",
       "exact Hessian by finite differences (false: limited-memory BFGS)"},
  };
}

}  // namespace maptr::config
