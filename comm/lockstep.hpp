#pragma once
// Who answers a tick (no DDS types here). Every live group and central answer every tick; an
// agent answers every tick it is assigned in, and, while idle (not assigned in the tick), only
// every kIdleAnswerEvery ticks, in a slot of its own, so that the plant hears it now and then.
// An idle agent applies 0 V by definition, so the plant loses nothing by not waiting for it.
// An agent answers the first tick it follows after a gap (its first tick after a start, or
// after a pause): the plant waits for a rejoining member.

namespace maptr::comm {

/// Ticks between two answers of an idle agent.
inline constexpr long long kIdleAnswerEvery = 10;

/// True when agent `index` of `side` (per_side agents a side) must answer tick `tick` while idle.
inline constexpr bool idle_answer_due(long long tick, int side, int index, int per_side) {
  return (tick + side * per_side + index) % kIdleAnswerEvery == 0;
}

}  // namespace maptr::comm
