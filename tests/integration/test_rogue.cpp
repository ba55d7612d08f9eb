// A rogue participant on the same host (ctest label `faults`): it reads the fleet's coordinates
// from fleet.json, as any local user can, joins the fleet's DDS domain through its discovery
// server and sends every kind of bad sample on every topic while a fleet runs. The run must end
// `ok` with the trace of the same run without the rogue, and every reject must be counted in
// summary.json.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <thread>
#include <tuple>

#include "comm/dds/checked_type.hpp"
#include "comm/dds/dds.hpp"
#include "comm/dds/fleet_ids.hpp"
#include "comm/dds/raw_type.hpp"
#include "comm/posix/shm_files.hpp"
#include "idl/maptrPubSubTypes.h"
#include "recorder/recorder.hpp"
#include "records/mcap.hpp"
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
    reply_ = p.writer(p.topic<msg::AgentReplyPubSubType>(comm::topic::kAgentReply), comm::Profile::kStream,
                      &m_[1]);
    group_ =
        p.writer(p.topic<msg::GroupStatusPubSubType>(comm::topic::kGroup), comm::Profile::kStream, &m_[2]);
    central_ = p.writer(p.topic<msg::CentralCommandPubSubType>(comm::topic::kCentral), comm::Profile::kStream,
                        &m_[3]);
    member_ = p.writer(p.topic<msg::MembershipEventPubSubType>(comm::topic::kMembership),
                       comm::Profile::kLatched, &m_[4]);
    control_ =
        p.writer(p.topic<msg::ControlPubSubType>(comm::topic::kControl), comm::Profile::kLatched, &m_[5]);
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
    tick(k + 2, now.t() + 0.02, msg::RUN_FINISHED);     // a forged end of the run
    tick(1000000000000ull, now.t(), msg::RUN_RUNNING);  // far in the future
    tick(k + 1, 50.0, msg::RUN_RUNNING);                // simulated time ahead (a clock for the launcher)
    tick(1, 0.01, msg::RUN_RUNNING);                    // a replay of an old tick
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
    g.active(
        std::vector<uint8_t>(now.sides()[msg::SIDE_L].active().size(), 0));  // a well-formed "nobody drives"
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

/// run.mcap of run `out` against its summary: each channel names its writer and the fleet's
/// verdict; the messages of the channels marked as dropped add up, kind by kind, to
/// summary.json's recording.rejected. A replay to a reader of the ticks sends only ticks the
/// fleet took and says how many messages it left out. Returns the file's dropped messages by kind.
std::map<std::string, long> expect_rejects_marked(const std::string& out, const nlohmann::json& s) {
  const auto f = maptr::records::mcap::read_file(out + "/run.mcap");
  std::map<std::string, long> dropped;
  // A tick by its number, time, speed and energy: a forgery differs from the real one in one.
  using TickKey = std::tuple<uint64_t, double, double, double>;
  const auto key = [](const msg::PlantTick& t) { return TickKey{t.tick(), t.t(), t.v_x(), t.energy_J()}; };
  std::set<TickKey> taken_ticks;
  for (const auto& m : f.messages) {
    const auto& ch = f.channels.at(m.channel_id);
    const std::string verdict = ch.metadata.at(maptr::recorder::kVerdictKey);
    if (verdict != "taken") ++dropped[verdict];
    msg::PlantTick t;
    if (verdict == "taken" && ch.topic == comm::topic::kTick &&
        comm::decode<msg::PlantTickPubSubType>(m.data, t))
      taken_ticks.insert(key(t));
    if (verdict == "taken")
      EXPECT_TRUE(comm::publishes(ch.metadata.at(maptr::recorder::kProcessKey), ch.topic));
  }
  long total = 0;
  for (const auto& [kind, n] : dropped) {
    EXPECT_EQ(s["recording"]["rejected"].value(kind, 0L), n) << kind << " " << s["recording"].dump();
    total += n;
  }
  EXPECT_EQ(s["recording"]["rejected"].size(), dropped.size()) << s["recording"].dump();
  comm::DdsOptions o;
  o.domain = private_domain();
  comm::Signal signal;
  comm::Inbox<msg::PlantTick> ticks(signal);
  {
    comm::Participant p("replay-reader", o);
    p.reader(p.topic<msg::PlantTickPubSubType>(comm::topic::kTick), comm::Profile::kReliableStream, &ticks,
             8192);
    const auto r = run_cli({"replay", out, "--rate", "4", "--domain", std::to_string(o.domain),
                            "--wait-reader", "30", "--quiet"},
                           out + "-replay", 300);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("left out    " + std::to_string(total) + " messages the fleet dropped"),
              std::string::npos)
        << r.output;
  }
  // Every tick the reader got is one the fleet took (a reliable keep-last writer may drop some
  // under load: a replay is for watching, so the test counts no losses).
  const auto got = ticks.drain();
  EXPECT_GT(got.size(), 0u);
  std::size_t foreign = 0;
  for (const auto& [t, h] : got) foreign += taken_ticks.count(key(t)) ? 0 : 1;
  EXPECT_EQ(foreign, 0u) << "the replay sent ticks the fleet did not take (of " << got.size() << ")";
  return dropped;
}

TEST(Rogue, EveryBadSampleIsRejectedCountedAndTheTraceIsUnchanged) {
  TempDir tmp;
  const std::string ref = tmp.path() + "/reference";
  auto r0 = run_cli(run_args(ref, kScenario), ref, 300);
  ASSERT_EQ(r0.exit_code, 0) << r0.output;
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
  // run.mcap keeps the rogue's samples, marked: it is no process of the fleet.
  auto dropped = expect_rejects_marked(out, s);
  std::cout << "run.mcap marks as dropped: " << nlohmann::json(dropped).dump() << "\n";
  EXPECT_GT(dropped["forged"], 0);
}

/// Participants that carry the rightful ids of group-L and central (the fleet's GUID prefix with
/// their base ids in the highest free id window: on a plain domain anyone can forge them), and
/// send what a faulty group or central could: malformed statuses and commands. Plus a raw
/// writer on the topics only the plant and the launcher read, with payloads nobody can decode.
class RightfulForger {
 public:
  explicit RightfulForger(const nlohmann::json& fleet) {
    const int agents = 16, stride = comm::fleet_stride(agents);
    const int top = (comm::rtps_max_participant_id(fleet["domain"].get<int>()) / stride - 1) * stride;
    auto options = [&](int base) {
      comm::DdsOptions o;
      o.domain = fleet["domain"];
      o.discovery_server = fleet["discovery_server"];
      o.lease_s = fleet["lease_s"];
      o.fleet_id = fleet["fleet_id"];
      o.participant_id = base < 0 ? -1 : top + base;
      return o;
    };
    group_p_ = std::make_unique<comm::Participant>("group-L", options(comm::group_participant_id(0)));
    group_ = group_p_->writer(group_p_->topic<msg::GroupStatusPubSubType>(comm::topic::kGroup),
                              comm::Profile::kStream, &m_[0]);
    group_p_->reader(group_p_->topic<msg::PlantTickPubSubType>(comm::topic::kTick), comm::Profile::kStream,
                     &ticks_);
    central_p_ = std::make_unique<comm::Participant>("central", options(comm::kCentralParticipantId));
    central_ = central_p_->writer(central_p_->topic<msg::CentralCommandPubSubType>(comm::topic::kCentral),
                                  comm::Profile::kStream, &m_[1]);
    raw_p_ = std::make_unique<comm::Participant>("rogue-raw", options(-1));
    for (const auto& t : comm::fleet_topics())
      if (t.topic == comm::topic::kControl || t.topic == comm::topic::kMembership ||
          t.topic == comm::topic::kGate || t.topic == comm::topic::kReady)
        raw_[t.topic] = raw_p_->writer(raw_p_->topic(t.topic, new comm::RawType(t.type_name, t.max_size)),
                                       t.profile, &m_[2 + raw_.size()]);
  }
  bool joined(msg::PlantTick& now, double timeout_s) {
    return wait_for(
        [&] {
          for (auto& m : m_)
            if (m.matched() < 1) return false;
          for (auto& [t, h] : ticks_.drain()) now = t;
          return now.tick() > 0;
        },
        timeout_s);
  }
  /// Malformed answers to tick `now`, under the rightful ids; returns how many were written.
  int malformed(const msg::PlantTick& now) {
    const std::size_t n = now.sides()[0].active().size();
    int written = 0;
    auto status = [&] {
      msg::GroupStatus g;
      g.tick(now.tick());
      g.side(msg::SIDE_L);
      g.active(std::vector<uint8_t>(n, 1));
      g.live(std::vector<uint8_t>(n, 1));
      g.ledger().wear_m(std::vector<double>(n, 0.0));  // would be a ledger going backwards
      g.ledger().active_time_s(std::vector<double>(n, 0.0));
      return g;
    };
    auto g = status();
    g.ledger().wear_m()[0] = kNaN;
    written += group_->write(&g);
    g = status();
    g.live(std::vector<uint8_t>(n + 1, 1));
    written += group_->write(&g);
    g = status();
    g.n_active(static_cast<uint16_t>(n + 1));
    written += group_->write(&g);
    g = status();
    g.level2_relaxed(kNaN);
    written += group_->write(&g);
    msg::CentralCommand c;
    c.tick(now.tick());
    c.v_x_ref(kNaN);
    written += central_->write(&c);
    c.v_x_ref(0.5);
    c.w_ref(1e9);
    written += central_->write(&c);
    return written;
  }
  /// One undecodable sample on each of control, membership, fault gate and readiness.
  void undecodable() {
    comm::RawSample s;
    s.bytes = std::string("\x00\x01\x00\x00\x01", 5);  // too short for any of them
    for (auto& [topic, w] : raw_) w->write(&s);
  }

 private:
  comm::Signal signal_;
  comm::Inbox<msg::PlantTick> ticks_{signal_};
  comm::MatchCounter m_[6];
  std::unique_ptr<comm::Participant> group_p_, central_p_, raw_p_;
  eprosima::fastdds::dds::DataWriter *group_ = nullptr, *central_ = nullptr;
  std::map<std::string, eprosima::fastdds::dds::DataWriter*> raw_;
};

/// A participant that is no process of the fleet and says every process is ready.
class ReadyForger {
 public:
  explicit ReadyForger(const nlohmann::json& fleet) {
    comm::DdsOptions o;
    o.domain = fleet["domain"];
    o.discovery_server = fleet["discovery_server"];
    o.lease_s = fleet["lease_s"];
    p_ = std::make_unique<comm::Participant>("ready-forger", o);
    w_ = p_->writer(p_->topic<msg::NodeReadyPubSubType>(comm::topic::kReady), comm::Profile::kLatched, &m_);
  }
  bool matched() const { return m_.matched() > 0; }
  /// One NodeReady per process of fleet.json, each carrying `pid`, or the process's own pid
  /// when pid is 0; returns how many were written.
  int forge(const nlohmann::json& fleet, pid_t pid) {
    int n = 0;
    for (const auto& p : fleet["processes"]) {
      msg::NodeReady r;
      r.name(p["name"].get<std::string>());
      r.kind(msg::NODE_AGENT);
      r.pid(static_cast<uint32_t>(pid != 0 ? pid : p["pid"].get<pid_t>()));
      r.ready(true);
      n += w_->write(&r) ? 1 : 0;
    }
    return n;
  }

 private:
  comm::MatchCounter m_;
  std::unique_ptr<comm::Participant> p_;
  eprosima::fastdds::dds::DataWriter* w_ = nullptr;
};


}  // namespace

TEST(Rogue, MalformedAnswersUnderTheRightfulIdsAndUndecodableSamplesAreCounted) {
  TempDir tmp;
  const std::string ref = tmp.path() + "/reference";
  auto r0 = run_cli(run_args(ref, kScenario), ref, 300);
  ASSERT_EQ(r0.exit_code, 0) << r0.output;

  const std::string out = tmp.path() + "/attacked";
  const pid_t launcher = start_cli(run_args(out, kScenario), tmp.path() + "/out.log");
  ASSERT_TRUE(wait_for([&] { return !read_json(out + "/fleet.json").is_null(); }, 60));
  int malformed = 0;
  constexpr int kUndecodable = 20;
  {
    RightfulForger forger(read_json(out + "/fleet.json"));
    msg::PlantTick now;
    ASSERT_TRUE(forger.joined(now, 60)) << "the forger did not join the fleet";
    for (int i = 0; i < kUndecodable; ++i) {
      malformed += forger.malformed(now);
      forger.undecodable();
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      now.tick(now.tick() + 5);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(500));  // everything delivered before it leaves
  }
  ASSERT_EQ(wait_child(launcher, 300), 0);
  const auto s = read_json(out + "/summary.json");
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["trace_sha256"], r0.summary["trace_sha256"]) << "malformed answers changed the run";
  const auto& plant = s["rejected_by_kind"]["plant"];
  const auto& launcher_kinds = s["rejected_by_kind"]["launcher"];
  std::cout << "malformed written: " << malformed << ", undecodable written per topic: " << kUndecodable
            << ", rejected_by_kind: " << s["rejected_by_kind"].dump() << "\n";
  // Every answer carries a malformed field: whatever its tick, what arrives is malformed (the
  // lock-step topics are best effort: some may be lost on the way).
  EXPECT_GT(plant.value("malformed", 0), 0);
  EXPECT_LE(plant.value("malformed", 0), malformed);
  // Control and membership are read by the plant alone, gates and readiness by the launcher alone.
  EXPECT_EQ(plant.value("undecodable", 0), 2 * kUndecodable);
  EXPECT_EQ(launcher_kinds.value("undecodable", 0), 2 * kUndecodable);
  // The wear watch never saw the ledgers go backwards.
  for (const char* side : {"L", "R"})
    EXPECT_EQ(s["plant"]["group_wear"][side]["regressions"], 0) << s["plant"]["group_wear"].dump();
  // run.mcap marks the malformed answers and every undecodable sample (the latched topics
  // deliver all 4 x 20 to the recorder).
  auto dropped = expect_rejects_marked(out, s);
  std::cout << "run.mcap marks as dropped: " << nlohmann::json(dropped).dump() << "\n";
  EXPECT_EQ(dropped["undecodable"], 4 * kUndecodable);
  EXPECT_GT(dropped["malformed"], 0);
  EXPECT_LE(dropped["malformed"], malformed);
}

TEST(Rogue, ForgedReadinessIsRejectedCountedAndSignalsNothing) {
  // A kill and a restart of L3, paced to the wall clock: the forger says every process is
  // ready from the first wave on, and keeps saying so (with the current pids of fleet.json,
  // and with the pid of a bystander process) through L3's restart.
  const std::vector<std::string> scenario = {"--duration", "14",        "--realtime", "--kill",
                                             "L3@4",       "--restart", "L3@7"};
  TempDir tmp;
  const std::string ref = tmp.path() + "/reference";
  auto r0 = run_cli(run_args(ref, scenario), ref, 300);
  ASSERT_EQ(r0.exit_code, 0) << r0.output;

  const pid_t bystander = fork();
  if (bystander == 0) {
    execl("/bin/sleep", "sleep", "600", nullptr);
    _exit(127);
  }
  const std::string out = tmp.path() + "/forged";
  const pid_t launcher = start_cli(run_args(out, scenario), tmp.path() + "/out.log");
  ASSERT_TRUE(wait_for([&] { return !read_json(out + "/fleet.json").is_null(); }, 60));
  int written = 0;
  {
    ReadyForger forger(read_json(out + "/fleet.json"));
    ASSERT_TRUE(wait_for([&] { return forger.matched(); }, 60)) << "the forger did not match the launcher";
    // Until the launcher ends: every 100 ms, once with the real pids, once with the bystander's.
    while (waitpid(launcher, nullptr, WNOHANG) == 0 && process_running(launcher)) {
      const auto fleet = read_json(out + "/fleet.json");
      if (fleet.contains("processes")) written += forger.forge(fleet, 0) + forger.forge(fleet, bystander);
      if (std::ifstream(out + "/summary.json").good()) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  ASSERT_EQ(wait_child(launcher, 300), 0) << read_text(tmp.path() + "/out.log");
  const bool bystander_alive = process_running(bystander);
  kill(bystander, SIGKILL);
  waitpid(bystander, nullptr, 0);
  EXPECT_TRUE(bystander_alive) << "a signal reached a process the launcher did not start";
  const auto s = read_json(out + "/summary.json");
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["trace_sha256"], r0.summary["trace_sha256"]) << "forged readiness changed the run";
  std::cout << "forged NodeReady written: " << written << ", rejected_ready: " << s["rejected_ready"].dump()
            << ", rejected_by_kind: " << s["rejected_by_kind"].dump() << "\n";
  ASSERT_GE(written, 40);
  // Every forgery the launcher received is counted (the latched writer delivers each one).
  EXPECT_GE(s["rejected_ready"]["forged"].get<long>(), 40);
  EXPECT_LE(s["rejected_ready"]["forged"].get<long>(), written);
  // The restarted L3 was announced once, after its own NodeReady.
  const std::string log = read_text(out + "/logs/launcher.log");
  EXPECT_NE(log.find("rejected a forged NodeReady"), std::string::npos);
  EXPECT_NE(log.find("L3 (pid"), std::string::npos);
  const auto started = log.find("restarted and ready");
  ASSERT_NE(started, std::string::npos) << log;
  EXPECT_EQ(log.find("restarted and ready", started + 1), std::string::npos) << "announced twice";
}
