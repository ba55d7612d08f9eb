// run.mcap of a 16-agent 10 s run: read back in C++ and counted against what the fleet
// published, checked with MCAP's TypeScript reader and Foxglove's OMG IDL deserialiser (when
// node is present), and replayed on a DDS domain to a reader of the fleet's types.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <tuple>

#include "comm/dds/checked_type.hpp"
#include "comm/dds/dds.hpp"
#include "comm/dds/raw_type.hpp"
#include "comm/lockstep/lockstep.hpp"
#include "idl/maptrPubSubTypes.h"
#include "recorder/recorder.hpp"
#include "records/mcap.hpp"
#include "records/trace.hpp"
#include "tests/hooks/hooks.hpp"
#include "tests/integration/fleet_runner.hpp"

using namespace maptr;
using maptr::testing::CliResult;
using maptr::testing::read_text;
using maptr::testing::TempDir;

namespace {

constexpr int kAgents = 16;

/// The run every test here reads (made once).
struct RecordedRun {
  TempDir dir;
  std::string out = dir.path() + "/run";
  CliResult result;
};

RecordedRun& recorded() {
  static RecordedRun run;
  static const bool made = [] {
    run.result = maptr::testing::run_cli(
        maptr::testing::run_args(run.out, {"--agents", std::to_string(kAgents), "--duration", "10"}), run.out,
        600);
    return true;
  }();
  (void)made;
  return run;
}

template <class PubSubType, class Msg>
Msg decode(const std::string& bytes) {
  Msg m;
  EXPECT_TRUE(comm::decode<PubSubType>(bytes, m));
  return m;
}

msg::PlantTick decode_tick(const std::string& bytes) {
  return decode<msg::PlantTickPubSubType, msg::PlantTick>(bytes);
}

std::map<std::string, std::vector<const records::mcap::Message*>> by_topic(const records::mcap::File& f) {
  std::map<std::string, std::vector<const records::mcap::Message*>> out;
  for (const auto& m : f.messages) out[f.channels.at(m.channel_id).topic].push_back(&m);
  return out;
}

}  // namespace

TEST(Record, RunMcapHoldsOneSamplePerPublicationOfTheFleet) {
  auto& run = recorded();
  ASSERT_EQ(run.result.exit_code, 0) << run.result.output;
  const auto f = records::mcap::read_file(run.out + "/run.mcap");
  const auto topics = by_topic(f);
  // Every topic, in one channel per writer: each names its writer, a process of the fleet that
  // publishes the topic, and the fleet's verdict "taken" (nobody sent anything bad).
  // (A channel appears with its writer's first sample: a topic nobody wrote on has none.)
  for (const char* t :
       {"maptr/tick", "maptr/agent_reply", "maptr/group", "maptr/central", "maptr/ready", "maptr/control",
        "maptr/hello"})
    EXPECT_TRUE(topics.count(t)) << t;
  for (const auto& [topic, messages] : topics) EXPECT_NE(comm::find_fleet_topic(topic), nullptr) << topic;
  std::map<std::string, std::set<std::string>> writers_of;
  for (const auto& [id, ch] : f.channels) {
    EXPECT_EQ(ch.metadata.at(recorder::kVerdictKey), "taken") << ch.topic;
    EXPECT_TRUE(comm::publishes(ch.metadata.at(recorder::kProcessKey), ch.topic))
        << ch.topic << " from " << ch.metadata.at(recorder::kProcessKey);
    EXPECT_EQ(ch.metadata.at(recorder::kWriterKey).size(), 24u);
    writers_of[ch.topic].insert(ch.metadata.at(recorder::kProcessKey));
    EXPECT_EQ(ch.message_encoding, "cdr");
    EXPECT_EQ(f.schemas.at(ch.schema_id).encoding, "omgidl");
    EXPECT_EQ(f.schemas.at(ch.schema_id).name.rfind("maptr::msg::", 0), 0u)
        << f.schemas.at(ch.schema_id).name;
  }
  EXPECT_EQ(writers_of["maptr/agent_reply"].size(), static_cast<std::size_t>(kAgents));
  EXPECT_EQ(writers_of["maptr/ready"].size(), static_cast<std::size_t>(kAgents + 4));
  EXPECT_EQ(writers_of["maptr/tick"], std::set<std::string>{"plant"});
  EXPECT_EQ(writers_of["maptr/hello"], std::set<std::string>{"plant"});
  EXPECT_EQ(writers_of["maptr/control"], std::set<std::string>{"launcher"});
  EXPECT_TRUE(run.result.summary["recording"]["rejected"].empty()) << run.result.summary["recording"].dump();
  // The summary's own check agrees: nothing the plant used is missing from run.mcap.
  EXPECT_TRUE(run.result.summary["recording"]["incomplete"].empty())
      << run.result.summary["recording"].dump();
  EXPECT_GT(run.result.summary["recording"]["recorded"].value("maptr/agent_reply", 0), 0);
  const auto ticks = static_cast<std::size_t>(run.result.summary.value("ticks", 0.0));
  // Ticks 0..ticks, one PlantTick each, and a copy for every tick the plant sent again.
  const auto repairs = run.result.summary["plant"].value("tick_repairs", std::size_t{0});
  EXPECT_EQ(topics.at("maptr/tick").size(), ticks + 1 + repairs);
  std::map<uint64_t, msg::PlantTick> sent;
  for (const auto* m : topics.at("maptr/tick")) {
    const auto t = decode_tick(m->data);
    sent[t.tick()] = t;
  }
  ASSERT_EQ(sent.size(), ticks + 1);
  // Every answer the lock-step needs is there (comm/lockstep/lockstep.hpp): each agent answers every tick
  // it is assigned in, every 10th while idle, and its first; groups and central every tick.
  std::set<std::tuple<uint64_t, int, int>> replies;
  for (const auto* m : topics.at("maptr/agent_reply")) {
    const auto r = decode<msg::AgentReplyPubSubType, msg::AgentReply>(m->data);
    replies.insert({r.tick(), static_cast<int>(r.side()), r.index()});
  }
  const int per_side = kAgents / 2;
  for (std::size_t k = 0; k < ticks; ++k)
    for (int side = 0; side < 2; ++side)
      for (int j = 0; j < per_side; ++j) {
        const bool needed = k == 0 || sent.at(k).sides()[side].active()[j] != 0 ||
                            comm::idle_answer_due(static_cast<long long>(k), side, j, per_side);
        if (needed) {
          EXPECT_TRUE(replies.count({k, side, j})) << "tick " << k << " side " << side << " agent " << j;
        }
      }
  std::set<std::pair<uint64_t, int>> statuses;
  for (const auto* m : topics.at("maptr/group")) {
    const auto g = decode<msg::GroupStatusPubSubType, msg::GroupStatus>(m->data);
    statuses.insert({g.tick(), static_cast<int>(g.side())});
  }
  EXPECT_EQ(statuses.size(), ticks * 2);
  std::set<uint64_t> commands;
  for (const auto* m : topics.at("maptr/central"))
    commands.insert(decode<msg::CentralCommandPubSubType, msg::CentralCommand>(m->data).tick());
  std::string missing;
  for (uint64_t k = 0; k < ticks && missing.size() < 200; ++k)
    if (!commands.count(k)) missing += " " + std::to_string(k);
  EXPECT_EQ(commands.size(), ticks) << "central's commands missing for ticks" << missing;
  EXPECT_EQ(topics.at("maptr/ready").size(), static_cast<std::size_t>(kAgents) + 4);
  // The plant's hello (its ports opened before tick 0), once.
  EXPECT_EQ(topics.at("maptr/hello").size(), 1u);
}

TEST(Record, EveryPlantTickEqualsItsTraceRow) {
  auto& run = recorded();
  ASSERT_EQ(run.result.exit_code, 0) << run.result.output;
  const auto f = records::mcap::read_file(run.out + "/run.mcap");
  std::map<uint64_t, msg::PlantTick> ticks;
  const auto topics = by_topic(f);
  for (const auto* m : topics.at("maptr/tick")) {
    const auto t = decode_tick(m->data);
    ticks[t.tick()] = t;
  }
  const auto rows = records::read_trace(run.out + "/trace.csv");
  ASSERT_FALSE(rows.empty());
  for (const auto& r : rows) {
    const auto it = ticks.find(static_cast<uint64_t>(r.tick));
    ASSERT_NE(it, ticks.end()) << "tick " << r.tick;
    const auto& t = it->second;
    // trace.csv prints 9 significant digits.
    EXPECT_NEAR(t.t(), r.t_s, 1e-6);
    EXPECT_NEAR(t.x(), r.x_m, 1e-8 * std::abs(r.x_m) + 1e-9);
    EXPECT_NEAR(t.v_x(), r.v_x_mps, 1e-8 * std::abs(r.v_x_mps) + 1e-9);
    EXPECT_NEAR(t.energy_J(), r.energy_J, 1e-8 * std::abs(r.energy_J) + 1e-9);
    EXPECT_NEAR(t.sides()[0].battery_V(), r.battery_V_L, 1e-8 * r.battery_V_L);
    EXPECT_EQ(t.sides()[1].n_active(), static_cast<int>(r.n_active_R));
  }
}

TEST(Record, McapReaderAndFoxgloveDeserialiserReadTheRun) {
  if (std::system("command -v node > /dev/null 2>&1 && command -v npm > /dev/null 2>&1") != 0)
    GTEST_SKIP()
        << "node or npm not found: the check with @mcap/core and @foxglove/omgidl-serialization is skipped "
           "(apt-get install nodejs npm to run it)";
  auto& run = recorded();
  ASSERT_EQ(run.result.exit_code, 0) << run.result.output;
  const std::string dir = MAPTR_MCAP_CHECK_DIR;
  // npm ci once per build tree (the versions of package-lock.json).
  if (!std::filesystem::exists(dir + "/node_modules/@mcap/support")) {
    const int npm = std::system(("cd '" + dir + "' && npm ci --no-audit --no-fund > npm-ci.log 2>&1").c_str());
    const std::string npm_out = read_text(dir + "/npm-ci.log");
    ASSERT_EQ(npm, 0) << "npm ci failed (" << dir << "/npm-ci.log):\n"
                      << npm_out.substr(npm_out.size() > 2000 ? npm_out.size() - 2000 : 0);
  }
  const std::string log = dir + "/check.log";
  const int rc =
      std::system(("node '" + dir + "/check_run_mcap.mjs' '" + run.out + "' > '" + log + "' 2>&1").c_str());
  const std::string out = read_text(log);
  std::cout << out;
  EXPECT_EQ(rc, 0) << out;
}

TEST(Record, AReplayIsSeenLiveByAReaderOfTheFleetsTypes) {
  auto& run = recorded();
  ASSERT_EQ(run.result.exit_code, 0) << run.result.output;
  const auto f = records::mcap::read_file(run.out + "/run.mcap");
  const std::size_t recorded_ticks = by_topic(f).at("maptr/tick").size();
  comm::DdsOptions o;
  o.domain = maptr::testing::private_domain();
  comm::Signal signal;
  comm::Inbox<msg::PlantTick> ticks(signal);
  {
    comm::Participant p("replay-reader", o);
    p.reader(p.topic<msg::PlantTickPubSubType>(comm::topic::kTick), comm::Profile::kReliableStream, &ticks,
             4096);
    // The replay waits for this reader before its first message.
    const auto r = maptr::testing::run_cli({"replay", run.out, "--rate", "4", "--domain",
                                            std::to_string(o.domain), "--wait-reader", "30", "--quiet"},
                                           run.out, 300);
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  const auto got = ticks.drain();
  ASSERT_EQ(got.size(), recorded_ticks);
  // The last tick ends the run (it has no trace row: the summary holds its figures); the one
  // before it is the trace's last row.
  const auto& last = got.back().first;
  EXPECT_EQ(last.run_state(), msg::RUN_FINISHED);
  EXPECT_NEAR(last.t(), run.result.summary.value("sim_time_s", 0.0), 1e-9);
  EXPECT_NEAR(last.energy_J(), run.result.summary.value("energy_J", 0.0), 1e-9);
  const auto rows = records::read_trace(run.out + "/trace.csv");
  const auto& before = got[got.size() - 2].first;
  EXPECT_EQ(before.tick(), static_cast<uint64_t>(rows.back().tick));
  EXPECT_NEAR(before.energy_J(), rows.back().energy_J, 1e-8 * rows.back().energy_J);
}

TEST(Record, AnAgentWhoseWriterTheRecorderNeverMatchesIsStartedAgainAndRecorded) {
  // The test hook hides the first start of L1's answer writer from the recorder, as if its
  // discovery had failed on the recorder's side only (seen once with 512 agents). The launcher
  // starts L1 again after the rematch interval, and run.mcap holds its answers.
  TempDir tmp;
  const std::string out = tmp.path() + "/deaf";
  const auto r = [&] {
    const maptr::testing::HookedBinaries hook(maptr::test_hooks::kRecorderDeafEnv, "L1");
    return maptr::testing::run_cli(maptr::testing::run_args(out, {"--agents", "8", "--duration", "2"}), out,
                                   300);
  }();
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.summary.value("status", ""), "ok");
  const auto rematched = r.summary.value("discovery_rematched", nlohmann::json::array());
  EXPECT_NE(std::find(rematched.begin(), rematched.end(), "L1"), rematched.end()) << r.summary.dump();
  const std::string text = read_text(out + "/logs/launcher.log");
  EXPECT_NE(text.find("recorder did not match L1's writer"), std::string::npos) << text;
  // The started-again L1 (side L, index 1) answers at least in its idle slots, one tick in ten:
  // run.mcap holds them.
  const auto f = records::mcap::read_file(out + "/run.mcap");
  int l1 = 0;
  const auto topics = by_topic(f);
  for (const auto* m : topics.at("maptr/agent_reply")) {
    const auto a = decode<msg::AgentReplyPubSubType, msg::AgentReply>(m->data);
    if (a.side() == msg::SIDE_L && a.index() == 1) ++l1;
  }
  EXPECT_GE(l1, 10) << "L1's answers in run.mcap";
}

// run.mcap's chunks compressed: zstd (the default) and lz4 hold every message of the same run
// uncompressed, byte for byte, in a fraction of the size.
TEST(Record, CompressedRecordingsHoldTheSameMessagesInLessSpace) {
  TempDir tmp;
  std::map<std::string, std::uintmax_t> size;
  std::map<std::string, records::mcap::File> file;
  for (const std::string c : {"none", "zstd", "lz4"}) {
    const std::string out = tmp.path() + "/" + c;
    const auto r = maptr::testing::run_cli(
        maptr::testing::run_args(out, {"--agents", "16", "--duration", "20", "--record-compression", c}), out,
        600);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    size[c] = std::filesystem::file_size(out + "/run.mcap");
    file[c] = records::mcap::read_file(out + "/run.mcap");
  }
  std::printf("run.mcap of 16 agents, 20 s: none %ju B, zstd %ju B (%.1f x smaller), lz4 %ju B (%.1f x)\n",
              size["none"], size["zstd"], double(size["none"]) / double(size["zstd"]), size["lz4"],
              double(size["none"]) / double(size["lz4"]));
  EXPECT_GE(size["none"], 3 * size["zstd"]);
  EXPECT_GT(size["none"], size["lz4"]);
  // The same run (the lock-step is deterministic): every tick decodes to the same state in each.
  // A loaded machine may make the plant send a tick again (plant.tick_repairs): the copies are
  // the same tick, so the ticks are compared by number.
  int undecodable = 0;  // every recorded tick must decode
  const auto ticks_of = [&](const records::mcap::File& f) {
    std::map<uint64_t, msg::PlantTick> out;
    const auto topics = by_topic(f);  // held: the loop runs over one of its vectors
    for (const auto* m : topics.at("maptr/tick")) {
      msg::PlantTickPubSubType type;
      eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<uint32_t>(m->data.size()));
      std::memcpy(payload.data, m->data.data(), m->data.size());
      payload.length = static_cast<uint32_t>(m->data.size());
      msg::PlantTick t;
      if (!type.deserialize(&payload, &t)) {
        ++undecodable;
        continue;
      }
      out.emplace(t.tick(), t);
    }
    return out;
  };
  const auto plain = ticks_of(file["none"]);
  for (const std::string c : {"zstd", "lz4"}) {
    const auto other = ticks_of(file[c]);
    ASSERT_EQ(plain.size(), other.size()) << c;
    for (const auto& [k, t] : plain) {
      const auto it = other.find(k);
      ASSERT_NE(it, other.end()) << c << " tick " << k;
      EXPECT_EQ(t.energy_J(), it->second.energy_J()) << c << " tick " << k;
      EXPECT_EQ(t.x(), it->second.x()) << c << " tick " << k;
    }
  }
  EXPECT_GE(plain.size(), 2000u);  // 20 s at 100 Hz: every tick is there
  EXPECT_EQ(undecodable, 0);
  std::printf("ticks compared: %zu per file; samples that did not decode: %d\n", plain.size(), undecodable);
}
