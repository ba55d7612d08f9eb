// Which processes hold a fault gate (deploy/fleet/children.hpp: gate_pending).
#include <gtest/gtest.h>

#include "deploy/fleet/children.hpp"

namespace {

using maptr::deploy::fleet::Child;
using maptr::deploy::fleet::gate_pending;

Child child(const std::string& name, bool running, bool awaiting_ready) {
  Child c;
  c.name = name;
  c.running = running;
  c.awaiting_ready = awaiting_ready;
  return c;
}

TEST(FaultGate, HeldUntilItsKilledProcessEnds) {
  EXPECT_TRUE(gate_pending({child("L1", true, false)}, {"L1"}, {}));
  EXPECT_FALSE(gate_pending({child("L1", false, false)}, {"L1"}, {}));
}

TEST(FaultGate, HeldUntilItsRestartedProcessIsReady) {
  EXPECT_TRUE(gate_pending({child("group-R", true, true)}, {}, {"group-R"}));
  EXPECT_FALSE(gate_pending({child("group-R", true, false)}, {}, {"group-R"}));
}

TEST(FaultGate, AnEarlierRestartNeverReadyDoesNotHoldLaterGates) {
  // group-R was restarted at an earlier gate and never reported ready: a later gate that pauses
  // L2 goes on at once instead of waiting for group-R until its limit.
  const std::vector<Child> kids = {child("group-R", true, true), child("L2", true, false)};
  EXPECT_FALSE(gate_pending(kids, {}, {}));
  EXPECT_FALSE(gate_pending(kids, {"R1"}, {"R2"}));
  EXPECT_TRUE(gate_pending(kids, {}, {"group-R"}));
}

}  // namespace
