// Who answers a tick (comm/lockstep/lockstep.hpp): an idle agent answers every kIdleAnswerEvery ticks, in
// a slot of its own, so that the idle agents of a side spread over the ticks.
#include <gtest/gtest.h>

#include <map>

#include "comm/lockstep/lockstep.hpp"

namespace {

using maptr::comm::idle_answer_due;
using maptr::comm::kIdleAnswerEvery;

TEST(Lockstep, EachIdleAgentAnswersOncePerPeriod) {
  constexpr int kPerSide = 8;
  for (int side = 0; side < 2; ++side)
    for (int index = 0; index < kPerSide; ++index) {
      int due = 0;
      for (long long k = 100; k < 100 + kIdleAnswerEvery; ++k) due += idle_answer_due(k, side, index, kPerSide);
      EXPECT_EQ(due, 1) << side << " " << index;
    }
}

TEST(Lockstep, IdleAnswersSpreadOverTheTicks) {
  constexpr int kPerSide = 10;
  std::map<long long, int> per_tick;
  for (long long k = 0; k < kIdleAnswerEvery; ++k)
    for (int side = 0; side < 2; ++side)
      for (int index = 0; index < kPerSide; ++index) per_tick[k] += idle_answer_due(k, side, index, kPerSide);
  for (const auto& [k, n] : per_tick) EXPECT_EQ(n, 2) << "tick " << k;  // 20 agents over 10 ticks
}

}  // namespace
