// An uncertified participant on a secure fleet's domain, for tools/secure_race.sh: a plain
// (unsecured) participant with a reader of the ticks and a writer of forged end-of-run ticks,
// every 20 ms until SIGTERM/SIGINT. The fleet's participants see its discovery traffic but no
// authentication succeeds, so nothing it writes reaches them. Prints what it received.
//
//   maptr_secure_intruder --domain D [--lease S]
#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>
#include <thread>

#include "comm/dds/dds.hpp"
#include "idl/maptrPubSubTypes.h"

namespace comm = maptr::comm;
namespace msg = maptr::msg;

namespace {
std::atomic<bool> stop{false};
void on_signal(int) { stop = true; }
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"An uncertified participant writing forged ticks on a secure fleet's domain"};
  comm::DdsOptions o;
  app.add_option("--domain", o.domain, "the fleet's DDS domain (fleet.json's domain)")->required()->check(CLI::Range(0, 232));
  app.add_option("--lease", o.lease_s, "participant lease, s")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  comm::Signal signal;
  comm::Inbox<msg::PlantTick> ticks{signal};
  comm::MatchCounter matched;
  uint64_t written = 0;
  std::size_t received = 0;
  {
    comm::Participant p("intruder", o);
    auto* topic = p.topic<msg::PlantTickPubSubType>(comm::topic::kTick);
    p.reader(topic, comm::Profile::kStream, &ticks);
    auto* w = p.writer(topic, comm::Profile::kStream, &matched);
    msg::PlantTick t;
    t.tick(1000000);
    t.run_state(msg::RUN_FINISHED);
    while (!stop) {
      w->write(&t);
      ++written;
      received += ticks.drain().size();
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  // Its own reader takes its own forgeries; anything beyond them came from the fleet.
  std::cout << "intruder: wrote " << written << " forged ticks, received " << received
            << " ticks (its own included), its writer matched " << matched.matched() << " readers\n";
  return 0;
}
