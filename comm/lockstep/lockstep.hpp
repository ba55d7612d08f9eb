#pragma once
// Who answers a tick (no DDS types here). Every live group and central answer every tick; an
// agent answers every tick it is assigned in, and, while idle (not assigned in the tick), only
// every kIdleAnswerEvery ticks, in a slot of its own, so that the plant hears it now and then.
// An idle agent applies 0 V by definition, so the plant loses nothing by not waiting for it.
// An agent answers the first tick it follows after a gap (its first tick after a start, or
// after a pause): the plant waits for a rejoining member.
//
// A lock-step sample is best effort: it goes only to the readers its writer has matched. So a
// process reports ready only once its lock-step writer has matched every reader the run needs,
// run.mcap's recorder included; a reader matching the writer is not enough.
#include <chrono>
#include <string>

namespace maptr::comm {

/// The readers run.mcap's recorder adds to a lock-step topic (0 or 1): it reads every topic
/// with `record: all`, and the plant's with `record: plant` (recorder/recorder.hpp).
inline int recorder_readers(const std::string& record, bool plant_topic) {
  return record == "all" || (record == "plant" && plant_topic) ? 1 : 0;
}

/// How long a follower's participant stays after the run's end while run.mcap records its
/// answers, so that the recorder takes the last of them (comm/lockstep/follower.cpp).
inline constexpr std::chrono::milliseconds kRecorderDrain{500};

/// Ticks between two answers of an idle agent.
inline constexpr long long kIdleAnswerEvery = 10;

/// True when agent `index` of `side` (per_side agents a side) must answer tick `tick` while idle.
inline constexpr bool idle_answer_due(long long tick, int side, int index, int per_side) {
  return (tick + side * per_side + index) % kIdleAnswerEvery == 0;
}

}  // namespace maptr::comm
