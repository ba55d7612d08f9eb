// Launch waves of a fleet (deploy/fleet/waves.hpp): which processes start next.
#include <gtest/gtest.h>

#include "deploy/fleet/waves.hpp"

using maptr::deploy::fleet::LaunchWaves;

namespace {
// 4 controllers and 10 agents, waves of 4 agents, 20 s wait.
constexpr std::size_t kProcesses = 14, kControllers = 4, kWave = 4;
constexpr double kWait = 20.0;

std::vector<bool> ready_up_to(std::size_t n, std::size_t total) {
  std::vector<bool> r(total, false);
  for (std::size_t i = 0; i < n; ++i) r[i] = true;
  return r;
}
}  // namespace

TEST(FleetWaves, FirstWaveIsTheControllersAndOneWaveOfAgents) {
  LaunchWaves w(kProcesses, kControllers, kWave, kWait);
  const auto r = w.first();
  EXPECT_EQ(r.begin, 0u);
  EXPECT_EQ(r.end, kControllers + kWave);
  EXPECT_TRUE(w.first().empty()) << "the first wave starts once";
}

TEST(FleetWaves, NextWaveWaitsUntilHalfOfTheLatestWaveIsReady) {
  LaunchWaves w(kProcesses, kControllers, kWave, kWait);
  w.first();
  // Controllers not ready yet do not hold agents back; fewer than half of the wave ready does.
  auto ready = ready_up_to(8, kProcesses);
  ready[0] = ready[1] = false;
  ready[5] = ready[6] = ready[7] = false;
  EXPECT_TRUE(w.next(ready, 1.0).empty());
  ready[7] = true;
  const auto r = w.next(ready, 1.0);
  EXPECT_EQ(r.begin, 8u);
  EXPECT_EQ(r.end, 12u);
}

TEST(FleetWaves, AnEarlierWaveMustBeWhollyReady) {
  LaunchWaves w(kProcesses, kControllers, kWave, kWait);
  w.first();
  EXPECT_EQ(w.next(ready_up_to(8, kProcesses), 1.0).end, 12u);
  // The latest wave (8..11) all ready, but agent 4 of the first one not: nothing starts.
  auto ready = ready_up_to(12, kProcesses);
  ready[4] = false;
  EXPECT_TRUE(w.next(ready, 1.0).empty());
  ready[4] = true;
  ready[10] = ready[11] = false;  // half of the latest wave is enough
  EXPECT_EQ(w.next(ready, 1.0).begin, 12u);
}

TEST(FleetWaves, NextWaveStartsAfterTheWaitEvenIfNotReady) {
  LaunchWaves w(kProcesses, kControllers, kWave, kWait);
  w.first();
  const std::vector<bool> none(kProcesses, false);
  EXPECT_TRUE(w.next(none, kWait).empty());
  const auto r = w.next(none, kWait + 0.1);
  EXPECT_EQ(r.begin, 8u);
  EXPECT_EQ(r.end, 12u);
}

TEST(FleetWaves, LastWaveIsShortAndThenNothingStarts) {
  LaunchWaves w(kProcesses, kControllers, kWave, kWait);
  w.first();
  const auto all = ready_up_to(kProcesses, kProcesses);
  w.next(all, 0.0);
  const auto last = w.next(all, 0.0);
  EXPECT_EQ(last.begin, 12u);
  EXPECT_EQ(last.end, kProcesses);
  EXPECT_TRUE(w.done());
  EXPECT_TRUE(w.next(all, 100.0).empty());
}

TEST(FleetWaves, SmallFleetStartsInOneWave) {
  LaunchWaves w(6, kControllers, 32, kWait);
  const auto r = w.first();
  EXPECT_EQ(r.end, 6u);
  EXPECT_TRUE(w.done());
}
