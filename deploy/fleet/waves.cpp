#include "deploy/fleet/waves.hpp"

#include <algorithm>

namespace maptr::deploy::fleet {

LaunchWaves::LaunchWaves(std::size_t processes, std::size_t controllers, std::size_t wave_size, double wait_s)
    : processes_(processes), controllers_(controllers), wave_size_(wave_size), wait_s_(wait_s) {}

LaunchWaves::Range LaunchWaves::take() {
  const std::size_t from = started_ == 0 ? std::min(controllers_, processes_) : started_;
  Range r{started_, std::min(processes_, from + wave_size_)};
  latest_ = from;
  started_ = r.end;
  return r;
}

LaunchWaves::Range LaunchWaves::first() { return started_ == 0 ? take() : Range{started_, started_}; }

LaunchWaves::Range LaunchWaves::next(const std::vector<bool>& ready, double since_last_s) {
  if (started_ == 0) return take();
  if (done()) return {started_, started_};
  // Every agent of the earlier waves ready, and at least half of the latest wave's.
  bool wave_ready = true;
  std::size_t latest_ready = 0;
  for (std::size_t i = controllers_; i < started_; ++i) {
    const bool r = i < ready.size() && ready[i];
    if (i >= latest_ && r) ++latest_ready;
    if (!r && i < latest_) wave_ready = false;
  }
  if (2 * latest_ready < started_ - latest_) wave_ready = false;
  if (!wave_ready && since_last_s <= wait_s_) return {started_, started_};
  return take();
}

}  // namespace maptr::deploy::fleet
