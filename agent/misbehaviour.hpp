#pragma once
// What an agent's software does wrong while its process runs on (scenario action fault, modes
// sensor, erratic and liar; docs/MODEL.md "Motor faults" has the motor's own):
//   sensor=B   the wheel speed it reads is off by B rad/s: its PID drives the motor wrong, and the
//              current it reports is the one its voltage gives at the speed it reads
//   erratic=S  seeded noise of S volts (standard deviation) on its voltage command, clamped to
//              the driver's range; the same for the same tick, side and index in every run
//   liar       when assigned it drives at the battery's voltage, and reports the current,
//              efficiency and state of a healthy agent in its place
// From the fault's first tick (config::first_tick_at) to the next fault or clear of the agent.
// A motor mode (open, short, ...) is the plant's to integrate: the agent behaves healthy.
// Pure: explicit time (ticks), no DDS.
#include <vector>

#include "control/level1/agent_core.hpp"

namespace maptr::agent {

enum class Misbehaviour { kNone, kSensor, kErratic, kLiar };

/// From tick `tick` on, the agent misbehaves so (kNone: it is healthy again).
struct MisbehaviourEvent {
  long long tick = 0;
  Misbehaviour kind = Misbehaviour::kNone;
  double value = 0.0;  ///< sensor: B [rad/s]; erratic: S [V]
};

/// An agent's Level 1 with its software faults.
class FaultyAgent {
 public:
  FaultyAgent(const control::AgentConfig& c, std::vector<MisbehaviourEvent> events, int side, int index);
  control::AgentOutput step(control::AgentInput in);
  /// The misbehaviour in force at the last step.
  Misbehaviour current() const { return now_.kind; }

 private:
  control::AgentConfig c_;
  control::AgentCore core_;
  std::vector<MisbehaviourEvent> events_;
  int side_, index_;
  MisbehaviourEvent now_;
};

/// Standard normal noise for (tick, side, index): a fixed function, the same in every run.
double seeded_noise(long long tick, int side, int index);

}  // namespace maptr::agent
