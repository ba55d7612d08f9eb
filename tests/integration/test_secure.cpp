// A secure domain (`maptr run --secure`, ctest label `secure`): the fleet runs with the trace of
// the same run without --secure; a participant without a certificate from the run's CA, and one
// with a certificate from another CA, receive nothing from the fleet and nothing they write is
// received by it; a participant with a certificate from the run's CA but permissions without
// the tick topic cannot create a tick writer, and its replies under an agent's name are dropped
// by the plant's sender check.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <thread>

#include "comm/dds/dds.hpp"
#include "comm/dds/fleet_guid.hpp"
#include "deploy/fleet/secure_domain.hpp"
#include "idl/maptrPubSubTypes.h"
#include "tests/integration/fleet_runner.hpp"

using namespace maptr::testing;
namespace msg = maptr::msg;
namespace comm = maptr::comm;
namespace fleet = maptr::deploy::fleet;

namespace {

// Paced to the wall clock so that the outsiders have most of the run to try.
const std::vector<std::string> kScenario = {"--agents", "8", "--duration", "15", "--realtime"};
constexpr double kRunTimeout_s = 400;
constexpr double kStartTimeout_s = 200;
constexpr double kAttack_s = 5.0;
/// How long an intruder's writer may take to be matched by the plant before a fresh one joins.
constexpr double kMatchWait_s = 5.0;
/// The tick index of the outsiders' forgeries (their own reader receives those).
constexpr uint64_t kForgedTick = 1000000;

/// The run's trace hash without --secure (computed once).
const nlohmann::json& plain_summary() {
  static nlohmann::json s = [] {
    TempDir tmp;
    const std::string out = tmp.path() + "/plain";
    return run_cli(run_args(out, kScenario), out, kRunTimeout_s).summary;
  }();
  return s;
}

/// Starts `maptr run --secure` and waits until its lock-step runs; returns the launcher's PID.
pid_t start_secure(const std::string& out, const std::string& log) {
  std::vector<std::string> extra = kScenario;
  extra.push_back("--secure");
  const pid_t pid = start_cli(run_args(out, extra), log);
  const bool running = wait_for(
      [&] { return read_text(out + "/logs/launcher.log").find("matched after") != std::string::npos; },
      kStartTimeout_s);
  EXPECT_TRUE(running) << read_text(log);
  return pid;
}

/// A participant outside the fleet: a reader of the ticks and a writer of forged ticks.
struct Outsider {
  Outsider(const std::string& name, const comm::DdsOptions& o) : p(name, o) {
    reader = p.reader(p.topic<msg::PlantTickPubSubType>(comm::topic::kTick), comm::Profile::kStream, &ticks);
    writer =
        p.writer(p.topic<msg::PlantTickPubSubType>(comm::topic::kTick), comm::Profile::kStream, &matched);
  }
  /// A forged end of the run, every 20 ms for `seconds`.
  void attack(double seconds) {
    msg::PlantTick t;
    t.tick(kForgedTick);
    t.run_state(msg::RUN_FINISHED);
    const auto t0 = std::chrono::steady_clock::now();
    while (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < seconds) {
      writer->write(&t);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  /// Ticks received from the fleet: any but the participant's own forgeries.
  int fleet_ticks() {
    int n = 0;
    for (auto& [t, h] : ticks.drain()) n += t.tick() != kForgedTick;
    return n;
  }
  // The listeners first: they outlive the participant, whose end still calls them.
  comm::Signal signal;
  comm::Inbox<msg::PlantTick> ticks{signal};
  comm::MatchCounter matched;
  comm::Participant p;
  eprosima::fastdds::dds::DataReader* reader = nullptr;
  eprosima::fastdds::dds::DataWriter* writer = nullptr;
};

int total_rejected(const nlohmann::json& s) {
  int n = 0;
  for (const auto& [name, count] : s["rejected_samples"].items()) n += count.get<int>();
  return n;
}

TEST(Secure, TheFleetRunsWithThePlainTraceAndOutsidersNeitherReceiveNorAreReceived) {
  const auto& plain = plain_summary();
  ASSERT_EQ(plain["status"], "ok") << plain.dump(2);
  TempDir tmp;
  const std::string out = tmp.path() + "/secure";
  const pid_t launcher = start_secure(out, tmp.path() + "/out.log");
  const auto fleet_json = read_json(out + "/fleet.json");
  ASSERT_FALSE(fleet_json.is_null());
  EXPECT_TRUE(fleet_json["discovery_server"].is_null());
  // The keys are the owner's only.
  struct stat st {};
  ASSERT_EQ(stat((out + "/security/plant.key.pem").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600);

  comm::DdsOptions plain_dds;
  plain_dds.domain = fleet_json["domain"];
  plain_dds.lease_s = fleet_json["lease_s"];
  // A certificate named "plant" from another CA, with every topic granted by that CA.
  const auto other = fleet::SecureDomain::create(tmp.path() + "/other-ca", plain_dds.domain);
  other.add_identity({"plant", {comm::topic::kTick, comm::topic::kGate, comm::topic::kReady}});
  comm::DdsOptions other_dds = plain_dds;
  other_dds.security_dir = other.files().dir;
  {
    Outsider no_cert("rogue", plain_dds);
    Outsider foreign("plant", other_dds);
    std::thread a([&] { no_cert.attack(kAttack_s); });
    foreign.attack(kAttack_s);
    a.join();
    EXPECT_EQ(no_cert.fleet_ticks(), 0) << "a participant without a certificate received the fleet's ticks";
    EXPECT_EQ(foreign.fleet_ticks(), 0) << "a certificate from another CA received the fleet's ticks";
    // Each forged-tick writer matched its own participant's reader at most, no reader of the fleet.
    EXPECT_LE(no_cert.matched.matched(), 1);
    EXPECT_LE(foreign.matched.matched(), 1);
  }
  ASSERT_EQ(wait_child(launcher, kRunTimeout_s), 0) << read_text(tmp.path() + "/out.log");
  const auto s = read_json(out + "/summary.json");
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["trace_sha256"], plain["trace_sha256"]) << "--secure or the outsiders changed the run";
  // Nothing they wrote even reached a process of the fleet.
  EXPECT_EQ(total_rejected(s), 0) << s["rejected_samples"].dump() << "\n"
                                   << s["rejected_by_kind"].dump() << "\n"
                                   << read_text(out + "/logs/plant.log");
}

TEST(Secure, ACertifiedParticipantCannotWriteTicksAndItsRepliesUnderAnotherNameAreDropped) {
  const auto& plain = plain_summary();
  ASSERT_EQ(plain["status"], "ok") << plain.dump(2);
  TempDir tmp;
  const std::string out = tmp.path() + "/secure";
  const std::string log = tmp.path() + "/out.log";
  std::vector<std::string> args = kScenario;
  args.push_back("--secure");
  const pid_t launcher = start_cli(run_args(out, args), log);
  // The run's CA exists once fleet.json does (the launcher writes both before its first wave).
  ASSERT_TRUE(wait_for([&] { return !read_json(out + "/fleet.json").is_null(); }, kStartTimeout_s))
      << read_text(log);
  const auto fleet_json = read_json(out + "/fleet.json");
  // An identity of the run's CA allowed to publish agent replies only.
  const fleet::SecureDomain run_ca(out + "/security", fleet_json["domain"]);
  run_ca.add_identity({"intruder", {comm::topic::kAgentReply}});
  comm::DdsOptions dds;
  dds.domain = fleet_json["domain"];
  dds.lease_s = fleet_json["lease_s"];
  dds.security_dir = run_ca.files().dir;
  const uint32_t fleet_id = fleet_json["fleet_id"];
  const int agents = std::stoi(kScenario.at(1));  // --agents
  // The first intruder joins while the fleet discovers itself, so that its authentication with
  // every process (the slow part) is done before the run starts. It has no endpoint until the
  // lock-step runs: no process of the fleet counts it while it waits for its members.
  std::vector<std::unique_ptr<comm::MatchCounter>> counters;  // outlive their participants
  auto p = std::make_unique<comm::Participant>("intruder", dds);
  ASSERT_TRUE(wait_for(
      [&] { return read_text(out + "/logs/launcher.log").find("matched after") != std::string::npos; },
      kStartTimeout_s))
      << read_text(log);
  EXPECT_THROW(p->writer(p->topic<msg::PlantTickPubSubType>(comm::topic::kTick), comm::Profile::kStream),
               std::runtime_error)
      << "permissions without the tick topic let a participant write ticks";
  // Its reply writer must match the plant's reader. A secure handshake between two participants
  // now and then never completes (the launcher starts a fleet process again for the same
  // reason, launcher.secure_rematch_s): a writer not matched by the plant within kMatchWait_s is
  // given up with its participant and a fresh intruder joins, while the run goes on.
  const auto plant_matched = [&](const comm::MatchCounter& m) {
    for (const auto& h : m.matched_readers())
      if (comm::writer_process(fleet_id, agents, h) == "plant") return true;
    return false;
  };
  const auto run_ended = [&] { return !read_json(out + "/summary.json").is_null(); };
  eprosima::fastdds::dds::DataWriter* w = nullptr;
  int attempts = 0;
  double matched_after_s = 0;
  while (!run_ended()) {
    if (attempts > 0) p = std::make_unique<comm::Participant>("intruder", dds);
    ++attempts;
    counters.push_back(std::make_unique<comm::MatchCounter>());
    const auto created = std::chrono::steady_clock::now();
    w = p->writer(p->topic<msg::AgentReplyPubSubType>(comm::topic::kAgentReply), comm::Profile::kStream,
                  counters.back().get());
    if (wait_for([&] { return plant_matched(*counters.back()) || run_ended(); }, kMatchWait_s) &&
        plant_matched(*counters.back())) {
      matched_after_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - created).count();
      break;
    }
    w = nullptr;
    p.reset();
  }
  ASSERT_NE(w, nullptr) << "no intruder's reply writer was matched by the plant's reader in " << attempts
                        << " attempts of " << kMatchWait_s << " s before the run ended";
  std::cout << "the intruder's writer (attempt " << attempts << ") matched the plant's reader " << matched_after_s
            << " s after its creation" << std::endl;
  const auto t0 = std::chrono::steady_clock::now();
  for (uint64_t k = 0; std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < kAttack_s;
       ++k) {
    msg::AgentReply r;  // a stop under L0's name
    r.tick(k);
    r.side(msg::SIDE_L);
    r.index(0);
    r.voltage_V(0.0);
    r.state(msg::AGENT_ACTIVE);
    w->write(&r);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  p.reset();
  ASSERT_EQ(wait_child(launcher, kRunTimeout_s), 0) << read_text(log);
  const auto s = read_json(out + "/summary.json");
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["trace_sha256"], plain["trace_sha256"]) << "the certified intruder changed the run";
  EXPECT_GT(s["rejected_samples"].value("plant", 0), 0) << s["rejected_samples"].dump();
}

}  // namespace
