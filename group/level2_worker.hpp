#pragma once
// The group's worker thread for Level 2: start() hands it the problem of tick k and returns at
// once; finish() at tick k + d returns the outcome, waiting only if the solve is still running
// (then the tick waits, and the run stays deterministic). One solver, used only by the worker.
// `pause` adds a wait after each solve: a slow solver for tests (set_level2_pause in
// group_node.hpp; zero in the product).
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

#include "control/level2/runner.hpp"

namespace maptr::group {

class Level2Worker : public control::Level2Runner {
 public:
  Level2Worker(bool oracle, std::chrono::milliseconds pause);
  ~Level2Worker() override;
  Level2Worker(const Level2Worker&) = delete;
  Level2Worker& operator=(const Level2Worker&) = delete;

  void start(const control::Level2Problem& p) override;
  control::Level2Outcome finish() override;

  /// Decisions finish() had to wait for, and all decisions finished so far.
  uint64_t waited() const { return waited_; }
  uint64_t finished() const { return finished_; }
  /// A solve is under way: started and not yet done (what the group's status tells the plant).
  bool solving();

 private:
  void loop();

  const bool oracle_;
  const std::chrono::milliseconds pause_;
  control::Level2Solver solver_;  // the worker's only
  std::mutex mutex_;
  std::condition_variable cv_;
  control::Level2Problem problem_;
  control::Level2Outcome outcome_;
  bool has_job_ = false, done_ = false, quit_ = false, solving_ = false;
  uint64_t waited_ = 0, finished_ = 0;
  std::thread thread_;  // last: started once everything above exists
};

}  // namespace maptr::group
