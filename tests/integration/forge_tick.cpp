// maptr_forge_tick: a participant that is not the plant publishing PlantTicks and FaultGates
// (an old tick index at a far simulated time) into a running fleet, for the tests that check
// that the launcher follows the plant's participant only. Joins the fleet from MAPTR_* like a
// process started by hand.
#include <chrono>
#include <cstdlib>
#include <thread>

#include "comm/dds/dds.hpp"
#include "idl/maptrPubSubTypes.h"

int main(int argc, char** argv) {
  namespace c = maptr::comm;
  const double seconds = argc > 1 ? std::atof(argv[1]) : 3.0;      // how long to publish, s
  const double forged_t = argc > 2 ? std::atof(argv[2]) : 1000.0;  // simulated time claimed, s
  c::Participant p("forger", c::options_from_env());
  auto* w_tick = p.writer(p.topic<maptr::msg::PlantTickPubSubType>(c::topic::kTick), c::Profile::kStream);
  auto* w_gate = p.writer(p.topic<maptr::msg::FaultGatePubSubType>(c::topic::kGate), c::Profile::kLatched);
  maptr::msg::PlantTick tick;
  tick.tick(1);  // long past: the fleet's followers have answered it already
  tick.t(forged_t);
  tick.v_x(99.0);
  maptr::msg::FaultGate gate;
  gate.tick(1);
  gate.t(forged_t);
  const auto t0 = std::chrono::steady_clock::now();
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < seconds) {
    w_tick->write(&tick);
    w_gate->write(&gate);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return 0;
}
