#pragma once
// Staggered launch of a fleet: the controllers (plant, central, two groups) and a first wave of
// agents, then one wave of agents at a time once every agent of the earlier waves and half of
// the latest wave's are ready (or after a wait): a herd of hundreds of participants starting at
// once starves the discovery server on two cores, and waiting for a whole wave leaves the
// machine idle while its last few are matched (256 agents: discovery 9.6 s waiting for the whole
// wave, 7.9 s for half of it, medians of 6 alternating runs). Pure: the caller says who is ready
// and how long it waited.
#include <cstddef>
#include <vector>

namespace maptr::deploy::fleet {

class LaunchWaves {
 public:
  struct Range {
    std::size_t begin = 0, end = 0;  ///< process indices [begin, end) to start now
    bool empty() const { return begin == end; }
  };

  /// `processes` in launch order, the first `controllers` of them not agents.
  LaunchWaves(std::size_t processes, std::size_t controllers, std::size_t wave_size, double wait_s);

  /// The first wave: the controllers and wave_size agents.
  Range first();
  /// The next wave, or an empty range: `ready[i]` says whether started process i is ready (or
  /// is not the launcher's to wait for); `since_last_s` is the wall time since the last wave.
  Range next(const std::vector<bool>& ready, double since_last_s);

  std::size_t started() const { return started_; }
  bool done() const { return started_ == processes_; }

 private:
  Range take();
  std::size_t processes_, controllers_, wave_size_, started_ = 0, latest_ = 0;
  double wait_s_;
};

}  // namespace maptr::deploy::fleet
