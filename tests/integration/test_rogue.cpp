// A rogue participant on the same host (ctest label `faults`): it reads the fleet's coordinates
// from fleet.json, as any local user can, joins the fleet's DDS domain through its discovery
// server and sends every kind of bad sample on every topic while a fleet runs. The run must end
// `ok` with the trace of the same run without the rogue, and every reject must be counted in
// summary.json.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <thread>

#include "comm/dds.hpp"
#include "idl/maptrPubSubTypes.h"
#include "tests/integration/fleet_runner.hpp"

using namespace maptr::testing;
namespace msg = maptr::msg;
namespace comm = maptr::comm;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Paced to the wall clock so that the rogue has the run's whole 20 s to join and attack.
const std::vector<std::string> kScenario = {"--duration", "20", "--realtime", "--kill", "L0@19.5"};
// Readers of maptr/tick besides the plant's own: 16 agents, 2 groups, central, the launcher.
constexpr int kTickReaders = 16 + 2 + 1 + 1;

/// Every writer of the protocol, from a participant that is no process of the fleet.
class Rogue {
 public:
  explicit Rogue(const nlohmann::json& fleet) {
    comm::DdsOptions o;
    o.domain = fleet["domain"];
    o.discovery_server = fleet["discovery_server"];
    o.lease_s = fleet["lease_s"];
    p_ = std::make_unique<comm::Participant>("rogue", o);
    auto& p = *p_;
    p.reader(p.topic<msg::PlantTickPubSubType>(comm::topic::kTick), comm::Profile::kStream, &ticks_);
    tick_ = p.writer(p.topic<msg::PlantTickPubSubType>(comm::topic::kTick), comm::Profile::kStream, &m_[0]);
    reply_ = p.writer(p.topic<msg::AgentReplyPubSubType>(comm::topic::kAgentReply), comm::Profile::kStream, &m_[1]);
    group_ = p.writer(p.topic<msg::GroupStatusPubSubType>(comm::topic::kGroup), comm::Profile::kStream, &m_[2]);
    central_ = p.writer(p.topic<msg::CentralCommandPubSubType>(comm::topic::kCentral), comm::Profile::kStream, &m_[3]);
    member_ =
        p.writer(p.topic<msg::MembershipEventPubSubType>(comm::topic::kMembership), comm::Profile::kLatched, &m_[4]);
    control_ = p.writer(p.topic<msg::ControlPubSubType>(comm::topic::kControl), comm::Profile::kLatched, &m_[5]);
    gate_ = p.writer(p.topic<msg::FaultGatePubSubType>(comm::topic::kGate), comm::Profile::kLatched, &m_[6]);
  }

  /// Waits until every writer found its readers (the tick writer every follower's) and a real
  /// tick arrived; returns that tick.
  bool wait_for_fleet(msg::PlantTick& last, double timeout_s) {
    return wait_for(
        [&] {
          for (auto& m : m_)
            if (m.matched() < 1) return false;
          if (m_[0].matched() < kTickReaders) return false;
          for (auto& [t, h] : ticks_.drain()) last = t;
          return last.tick() > 0;
        },
        timeout_s);
  }

  /// One of each kind of bad sample, built around the current tick k.
  void attack(const msg::PlantTick& now) {
    const uint64_t k = now.tick();
    auto tick = [&](uint64_t n, double t, msg::RunState state) {
      msg::PlantTick x = now;
      x.tick(n);
      x.t(t);
      x.run_state(state);
      tick_->write(&x);
    };
    tick(k + 2, now.t() + 0.02, msg::RUN_FINISHED);  // a forged end of the run
    tick(1000000000000ull, now.t(), msg::RUN_RUNNING);  // far in the future
    tick(k + 1, 50.0, msg::RUN_RUNNING);             // simulated time ahead (a clock for the launcher)
    tick(1, 0.01, msg::RUN_RUNNING);                 // a replay of an old tick
    msg::PlantTick nan = now;
    nan.tick(k + 1);
    nan.v_x(kNaN);
    tick_->write(&nan);

    // Out-of-range enum values go on the wire as any 32-bit number would.
    auto side_of = [](int s) { return static_cast<msg::Side>(s); };
    auto reply = [&](int side, uint16_t index, double v, uint64_t at) {
      msg::AgentReply r;
      r.tick(at);
      r.side(side_of(side));
      r.index(index);
      r.voltage_V(v);
      r.state(msg::AGENT_ACTIVE);
      reply_->write(&r);
    };
    reply(0, 1, kNaN, k);
    reply(2, 0, 5.0, k);
    reply(0, 999, 5.0, k);
    reply(0, 1, 1000.0, k);
    reply(0, 0, std::numeric_limits<double>::infinity(), k);
    for (uint64_t at = k; at < k + 50; ++at) reply(0, 0, 0.0, at);  // replies under L0's name

    msg::GroupStatus g;
    g.tick(k);
    g.side(msg::SIDE_L);
    g.active(std::vector<uint8_t>(100000, 1));
    group_->write(&g);
    g.active(std::vector<uint8_t>(now.sides()[msg::SIDE_L].active().size(), 0));  // a well-formed "nobody drives"
    for (uint64_t at = k; at < k + 50; ++at) {
      g.tick(at);
      group_->write(&g);
    }
    g.side(side_of(7));
    group_->write(&g);

    msg::CentralCommand c;
    c.tick(k);
    c.phidot_ref()[msg::SIDE_L] = kNaN;
    central_->write(&c);
    c.phidot_ref()[msg::SIDE_L] = 1e9;
    central_->write(&c);
    for (uint64_t at = k; at < k + 50; ++at) {  // a well-formed "stop"
      c.tick(at);
      c.phidot_ref()[msg::SIDE_L] = 0.0;
      c.phidot_ref()[msg::SIDE_R] = 0.0;
      central_->write(&c);
    }

    msg::MembershipEvent e;  // a forged death of L1
    e.seq(1000);
    e.name("L1");
    e.node_kind(msg::NODE_AGENT);
    e.side(msg::SIDE_L);
    e.index(1);
    e.kind(msg::MEMBER_DIED);
    member_->write(&e);
    msg::Control stop;
    stop.command(msg::CONTROL_STOP);
    stop.seq(1000);
    control_->write(&stop);
    msg::FaultGate gate;  // a gate at t = 50 s would fire the scheduled kill of L0 now
    gate.tick(k);
    gate.t(50.0);
    gate_->write(&gate);
  }

 private:
  comm::Signal signal_;
  comm::Inbox<msg::PlantTick> ticks_{signal_};
  comm::MatchCounter m_[7];
  std::unique_ptr<comm::Participant> p_;
  eprosima::fastdds::dds::DataWriter *tick_, *reply_, *group_, *central_, *member_, *control_, *gate_;
};

TEST(Rogue, EveryBadSampleIsRejectedCountedAndTheTraceIsUnchanged) {
  TempDir tmp;
  const std::string ref = tmp.path() + "/reference";
  auto r0 = run_cli(run_args(ref, kScenario), ref, 300);
  ASSERT_EQ(r0.summary["status"], "ok") << r0.output;

  const std::string out = tmp.path() + "/attacked";
  const pid_t launcher = start_cli(run_args(out, kScenario), tmp.path() + "/out.log");
  ASSERT_TRUE(wait_for([&] { return !read_json(out + "/fleet.json").is_null(); }, 60));
  {
    Rogue rogue(read_json(out + "/fleet.json"));
    msg::PlantTick now;
    ASSERT_TRUE(rogue.wait_for_fleet(now, 60)) << "the rogue did not join the fleet";
    for (int i = 0; i < 3; ++i) {
      rogue.attack(now);
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
      now.tick(now.tick() + 20);
    }
  }
  ASSERT_EQ(wait_child(launcher, 300), 0);
  const auto s = read_json(out + "/summary.json");
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["trace_sha256"], r0.summary["trace_sha256"]) << "the rogue changed the run";
  EXPECT_DOUBLE_EQ(s["distance_m"].get<double>(), r0.summary["distance_m"].get<double>());
  // The scheduled kill fired at its own time, not at the forged gate's.
  ASSERT_EQ(s["failures"].size(), 1u) << s["failures"].dump();
  EXPECT_DOUBLE_EQ(s["failures"][0]["at_s"].get<double>(), 19.5) << s["failures"].dump();
  // Every process that received bad samples says how many.
  const auto& rejected = s["rejected_samples"];
  ASSERT_TRUE(rejected.is_object()) << s.dump(2);
  std::cout << "rejected_samples: " << rejected.dump() << "\n";
  EXPECT_GT(rejected.value("plant", 0), 0);
  EXPECT_GT(rejected.value("launcher", 0), 0);
  EXPECT_GT(rejected.value("central", 0), 0);
  EXPECT_GT(rejected.value("group-L", 0), 0);
  EXPECT_GT(rejected.value("L0", 0), 0);
}

}  // namespace
