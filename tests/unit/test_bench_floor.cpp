// The IPC floor probe of `maptr bench`: real processes and pipes, no timing asserted.
#include <gtest/gtest.h>

#include "deploy/studies/bench/floor.hpp"

namespace maptr::deploy {
namespace {

TEST(BenchFloor, EveryWorkerAnswersEveryRoundAndBlocksInBetween) {
  const FloorResult f = measure_floor(4, 300, 20);
  EXPECT_EQ(f.workers, 4);
  EXPECT_EQ(f.rounds, 300);
  EXPECT_GT(f.median_us, 0.0);
  EXPECT_GE(f.p99_us, f.median_us);
  // Each worker blocks in read() between rounds, and the hub waits for the answers: at least
  // one context switch per worker per round, whatever the machine's speed.
  EXPECT_GE(f.ctx_switches_per_round, 4.0);
}

TEST(BenchFloor, RefusesAnEmptyProbe) {
  EXPECT_THROW(measure_floor(0), std::invalid_argument);
  EXPECT_THROW(measure_floor(3, 0), std::invalid_argument);
  EXPECT_THROW(measure_floor(3, 10, 1, -1), std::invalid_argument);
}

TEST(BenchFloor, WorkersWithAWorkingSetStillAnswerEveryRound) {
  const FloorResult f = measure_floor(3, 200, 20, 256);
  EXPECT_EQ(f.workers, 3);
  EXPECT_EQ(f.touch_kb, 256);
  EXPECT_EQ(f.rounds, 200);
  EXPECT_GT(f.median_us, 0.0);
  EXPECT_GE(f.ctx_switches_per_round, 3.0);
}

}  // namespace
}  // namespace maptr::deploy
