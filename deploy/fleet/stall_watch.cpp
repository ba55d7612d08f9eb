#include "deploy/fleet/stall_watch.hpp"

#include <cstdio>

namespace maptr::deploy::fleet {

void StallWatch::start(double now_s) {
  started_ = true;
  last_progress_s_ = now_s;
}

void StallWatch::observe(double t_sim_s, long gates, double now_s) {
  if (t_sim_s > t_sim_s_ || gates > gates_) last_progress_s_ = now_s;
  if (t_sim_s > t_sim_s_) t_sim_s_ = t_sim_s;
  if (gates > gates_) gates_ = gates;
}

std::string stalled_status(const StallWatch& w) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "aborted: stalled: no tick from the plant for %.0f s (last at t=%.2f s)",
                w.limit_s(), w.last_t_sim_s() < 0.0 ? 0.0 : w.last_t_sim_s());
  return buf;
}

}  // namespace maptr::deploy::fleet
