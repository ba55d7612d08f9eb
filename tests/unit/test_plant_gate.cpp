// Plant fault gate (plant/fault_gate.hpp): the gate schedule in simulated time and the wait
// for the launcher's answer and its membership events.
#include <gtest/gtest.h>

#include "plant/fault_gate.hpp"

namespace {

using maptr::plant::FaultGate;

/// Ticks the plant holds over a run of `ticks` ticks at `hz` (t_k = k / hz as the plant computes it).
std::vector<long long> gate_ticks(FaultGate g, double hz, long long ticks) {
  const double dt = 1.0 / hz;
  std::vector<long long> out;
  for (long long k = 0; k < ticks; ++k)
    if (g.due(k * dt)) out.push_back(k);
  return out;
}

TEST(PlantFaultGate, GateTicksAt100Hz) {
  EXPECT_EQ(gate_ticks(FaultGate({5.0, 8.0}, 120.0), 100.0, 1000), (std::vector<long long>{500, 800}));
  // Between two ticks: the first tick after it.
  EXPECT_EQ(gate_ticks(FaultGate({5.004}, 120.0), 100.0, 1000), std::vector<long long>{501});
  // At t = 0 and past the end.
  EXPECT_EQ(gate_ticks(FaultGate({0.0, 20.0}, 120.0), 100.0, 1000), std::vector<long long>{0});
}

TEST(PlantFaultGate, FaultsAtTheSameTimeGiveOneGate) {
  FaultGate g({8.0, 5.0, 5.0}, 120.0);
  EXPECT_EQ(g.times(), (std::vector<double>{5.0, 8.0}));
  EXPECT_EQ(gate_ticks(g, 100.0, 1000), (std::vector<long long>{500, 800}));
  // Two faults within one tick: one gate.
  EXPECT_EQ(gate_ticks(FaultGate({5.001, 5.002}, 120.0), 100.0, 1000), std::vector<long long>{501});
}

TEST(PlantFaultGate, ReleasedAfterTheAnswerAndItsMembershipEvents) {
  FaultGate g({5.0}, 120.0);
  g.hold(500);
  EXPECT_FALSE(g.released(0));
  g.on_open(499, 0);  // an answer for another tick
  EXPECT_FALSE(g.released(10));
  g.on_open(500, 3);  // the launcher published 3 membership events before its answer
  EXPECT_FALSE(g.released(2));
  EXPECT_TRUE(g.released(3));
  EXPECT_TRUE(g.released(4));
  g.hold(800);  // the next gate starts closed
  EXPECT_FALSE(g.released(10));
}

TEST(PlantFaultGate, TimesOut) {
  FaultGate g({5.0}, 120.0);
  EXPECT_FALSE(g.timed_out(119.9));
  EXPECT_TRUE(g.timed_out(120.1));
}

}  // namespace
