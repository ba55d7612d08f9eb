// comm/ on its own: the fleet's participant-id and GUID plan, the tick's per-side data on the
// wire and the followers' check of it, the shipped QoS profiles and their override through
// FASTRTPS_DEFAULT_PROFILES_FILE, the bounded deletion of a participant. Real DDS participants, no fleet.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "comm/dds/dds.hpp"
#include "comm/dds/fleet_guid.hpp"
#include "comm/lockstep/follower.hpp"
#include "idl/maptrPubSubTypes.h"

namespace maptr::comm {
namespace {

namespace rtps = eprosima::fastrtps::rtps;

rtps::InstanceHandle_t handle_of(const rtps::GuidPrefix_t& prefix) {
  rtps::GUID_t guid;
  guid.guidPrefix = prefix;
  guid.entityId = rtps::EntityId_t(0x103);  // any user writer
  return rtps::InstanceHandle_t(guid);
}

TEST(FleetIds, NamesAndIdsOfA16AgentFleet) {
  EXPECT_EQ(base_participant_id("plant", 16), kPlantParticipantId);
  EXPECT_EQ(base_participant_id("group-R", 16), 5);
  EXPECT_EQ(base_participant_id("L0", 16), 6);
  EXPECT_EQ(base_participant_id("R7", 16), 6 + 15);
  EXPECT_EQ(base_participant_id("R8", 16), -1);
  EXPECT_EQ(base_participant_id("rogue", 16), -1);
  // A restart takes the same base in the next id window (stride N + 6 = 22).
  EXPECT_EQ(participant_name(6 + 3 * 22, 16), "L0");
  EXPECT_EQ(participant_name(2 + 22, 16), "plant");
  EXPECT_EQ(participant_name(1, 16), "launcher");
  for (const std::string name : {"plant", "central", "group-L", "group-R", "L5", "R3"})
    EXPECT_EQ(participant_name(base_participant_id(name, 16), 16), name);
  // The numeric ids the plant checks every sample against are the same plan.
  EXPECT_EQ(base_participant_id("central", 16), kCentralParticipantId);
  for (int side = 0; side < 2; ++side) {
    EXPECT_EQ(base_participant_id(side == 0 ? "group-L" : "group-R", 16), group_participant_id(side));
    for (int j = 0; j < 8; ++j)
      EXPECT_EQ(participant_name(agent_participant_id(side, j, 16), 16), (side == 0 ? "L" : "R") + std::to_string(j));
  }
}

TEST(FleetIds, AWriterIsKnownByItsFleetAndParticipant) {
  const uint32_t fleet = 0x5eed1234;
  const auto plant = handle_of(fleet_guid_prefix(fleet, kPlantParticipantId));
  EXPECT_TRUE(written_by(fleet, 16, plant, "plant"));
  EXPECT_FALSE(written_by(fleet, 16, plant, "central"));
  // The same participant id of another fleet is not this fleet's plant.
  EXPECT_FALSE(written_by(fleet + 2, 16, plant, "plant"));
  // A writer with Fast DDS's own prefix (a participant started without a fleet id).
  rtps::GuidPrefix_t other;
  other.value[0] = 0x01;
  other.value[1] = 0x0f;
  EXPECT_FALSE(fleet_participant(fleet, handle_of(other)).has_value());
  // Agent L3 restarted twice still writes as L3, and only as L3.
  const auto l3 = handle_of(fleet_guid_prefix(fleet, base_participant_id("L3", 16) + 2 * fleet_stride(16)));
  EXPECT_TRUE(written_by(fleet, 16, l3, "L3"));
  EXPECT_FALSE(written_by(fleet, 16, l3, "L4"));
  EXPECT_TRUE(written_by_id(fleet, 16, l3, agent_participant_id(0, 3, 16)));
  EXPECT_FALSE(written_by_id(fleet, 16, l3, kPlantParticipantId));
}

TEST(FleetIds, PrefixesKeepFastDdsSameHostAndDistinctProcesses) {
  const auto a = fleet_guid_prefix(7, 2), b = fleet_guid_prefix(7, 3);
  rtps::GUID_t ga, gb;
  ga.guidPrefix = a;
  gb.guidPrefix = b;
  EXPECT_TRUE(ga.is_on_same_host_as(gb));
  EXPECT_FALSE(ga.is_on_same_process_as(gb));  // else Fast DDS would deliver intraprocess
}

/// A well-formed tick of 2 x 4 agents whose sides differ in every field.
msg::PlantTick two_sided_tick() {
  msg::PlantTick t;
  t.tick(42);
  t.t(0.42);
  for (int s = 0; s < 2; ++s) {
    msg::SideTick& side = t.sides()[s];
    side.phidot(100.0 + s);
    side.battery_V(23.0 - s);
    side.V_active(11.0 + s);
    side.discharge_mAh(5.0 + s);
    side.phidot_ref(101.0 + s);
    side.active(s == msg::SIDE_L ? std::vector<uint8_t>{1, 1, 0, 0} : std::vector<uint8_t>{1, 0, 0, 0});
    side.live(std::vector<uint8_t>{1, 1, 1, static_cast<uint8_t>(s)});
    side.wake(side.active());
    side.group_stamp(40 + s);
    side.n_active(static_cast<uint16_t>(2 - s));
    side.relay_count(static_cast<uint16_t>(1 + s));
  }
  t.run_state(msg::RUN_FINISHED);
  return t;
}

TEST(TickWire, PerSideDataAndEnumsSurviveSerialization) {
  msg::PlantTick sent = two_sided_tick();
  msg::PlantTickPubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&sent)());
  ASSERT_TRUE(type.serialize(&sent, &payload));
  msg::PlantTick got;
  ASSERT_TRUE(type.deserialize(&payload, &got));
  EXPECT_TRUE(got == sent);
  EXPECT_EQ(got.run_state(), msg::RUN_FINISHED);
  EXPECT_EQ(got.sides()[msg::SIDE_R].active(), (std::vector<uint8_t>{1, 0, 0, 0}));
  EXPECT_EQ(got.sides()[msg::SIDE_L].relay_count(), 1);
  EXPECT_EQ(got.sides()[msg::SIDE_R].group_stamp(), 41);

  msg::CentralCommand c;
  c.phidot_ref({40.0, -40.0});
  c.relay_count_for({3, 5});
  msg::CentralCommandPubSubType ctype;
  eprosima::fastrtps::rtps::SerializedPayload_t cpayload(ctype.getSerializedSizeProvider(&c)());
  ASSERT_TRUE(ctype.serialize(&c, &cpayload));
  msg::CentralCommand cgot;
  ASSERT_TRUE(ctype.deserialize(&cpayload, &cgot));
  EXPECT_EQ(cgot.phidot_ref()[msg::SIDE_R], -40.0);
  EXPECT_EQ(cgot.relay_count_for()[msg::SIDE_L], 3);
}

TEST(TickWire, AFollowerChecksEachSide) {
  EXPECT_TRUE(tick_valid(two_sided_tick(), 4));
  EXPECT_FALSE(tick_valid(two_sided_tick(), 5));  // masks of another fleet size
  for (int s = 0; s < 2; ++s) {
    msg::PlantTick t = two_sided_tick();
    t.sides()[s].phidot_ref(std::nan(""));
    EXPECT_FALSE(tick_valid(t, 4)) << "side " << s;
    t = two_sided_tick();
    t.sides()[s].live(std::vector<uint8_t>{1, 1, 1});
    EXPECT_FALSE(tick_valid(t, 4)) << "side " << s;
    t = two_sided_tick();
    t.sides()[s].battery_V(-1.0);
    EXPECT_FALSE(tick_valid(t, 4)) << "side " << s;
    // A braking side (H-bridge) applies down to -V_B: its mean may be negative, not beyond.
    t = two_sided_tick();
    t.sides()[s].V_active(-0.5 * t.sides()[s].battery_V());
    EXPECT_TRUE(tick_valid(t, 4)) << "side " << s;
    t.sides()[s].V_active(-1.5 * t.sides()[s].battery_V());
    EXPECT_FALSE(tick_valid(t, 4)) << "side " << s;
  }
}

DdsOptions private_options() {
  DdsOptions o;
  o.domain = 200 + static_cast<int>(getpid()) % 30;
  o.shm = false;
  return o;
}

TEST(QosProfiles, TheShippedProfilesGiveTheProtocolsQos) {
  ASSERT_TRUE(std::ifstream(qos_profiles_file()).good()) << qos_profiles_file();
  Participant p("qos-test", private_options());
  auto* t = p.topic<msg::PlantTickPubSubType>(topic::kTick);
  auto* w = p.writer(t, Profile::kStream);
  const auto wq = w->get_qos();
  // Lock-step data: best effort (the lock-step repairs a loss itself), synchronous, and no
  // endpoint lease (the participant's lease tells a death).
  EXPECT_EQ(wq.reliability().kind, eprosima::fastdds::dds::BEST_EFFORT_RELIABILITY_QOS);
  EXPECT_EQ(wq.durability().kind, eprosima::fastdds::dds::VOLATILE_DURABILITY_QOS);
  EXPECT_EQ(wq.history().kind, eprosima::fastdds::dds::KEEP_LAST_HISTORY_QOS);
  EXPECT_EQ(wq.history().depth, 32);
  EXPECT_EQ(wq.publish_mode().kind, eprosima::fastdds::dds::SYNCHRONOUS_PUBLISH_MODE);
  EXPECT_EQ(wq.liveliness().lease_duration, eprosima::fastrtps::c_TimeInfinite);
  auto* l = p.writer(p.topic<msg::MembershipEventPubSubType>(topic::kMembership), Profile::kLatched);
  EXPECT_EQ(l->get_qos().durability().kind, eprosima::fastdds::dds::TRANSIENT_LOCAL_DURABILITY_QOS);
  EXPECT_EQ(l->get_qos().history().kind, eprosima::fastdds::dds::KEEP_ALL_HISTORY_QOS);
  EXPECT_EQ(l->get_qos().reliability().kind, eprosima::fastdds::dds::RELIABLE_RELIABILITY_QOS);
}

// This host's shared-memory locator carries the kind and the unicast mark Fast DDS gives it;
// the port is left to Fast DDS (the participant's well-known port).
TEST(ShmLocator, IsAUnicastSharedMemoryLocatorWithoutAPort) {
  const auto loc = shm_unicast_locator();
  EXPECT_EQ(loc.kind, LOCATOR_KIND_SHM);
  EXPECT_EQ(loc.port, 0u);
  EXPECT_EQ(loc.address[0], 'U');
  EXPECT_EQ(shm_unicast_locator(), loc);  // the same host id every time
}

TEST(QosProfiles, FastDdsDefaultProfilesFileReplacesTheShippedOne) {
  // A copy of the shipped file with a deeper tick history, used through the Fast DDS variable
  // by a fresh process (profiles load once per process).
  std::stringstream xml;
  xml << std::ifstream(qos_profiles_file()).rdbuf();
  std::string text = xml.str();
  const std::string from = "<historyQos><kind>KEEP_LAST</kind><depth>32</depth></historyQos>";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), "<historyQos><kind>KEEP_LAST</kind><depth>7</depth></historyQos>");
  char path[] = "/tmp/maptr-qos-XXXXXX";
  const int fd = mkstemp(path);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(write(fd, text.data(), text.size()), static_cast<ssize_t>(text.size()));
  close(fd);
  const pid_t child = fork();
  if (child == 0) {
    setenv("FASTRTPS_DEFAULT_PROFILES_FILE", path, 1);
    setenv("MAPTR_QOS_CHILD", "7", 1);
    execl("/proc/self/exe", "test_comm", "--gtest_filter=QosProfiles.DISABLED_ChildProcessReportsTheTickHistoryDepth",
          "--gtest_also_run_disabled_tests",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  int st = 0;
  waitpid(child, &st, 0);
  unlink(path);
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 0) << "the writer did not take its history depth from the override file";
}

// Run only by the test above, in a fresh process (hence DISABLED_ for the test runner): passes
// when the tick writer's history depth is the one MAPTR_QOS_CHILD names.
TEST(QosProfiles, DISABLED_ChildProcessReportsTheTickHistoryDepth) {
  const char* want = std::getenv("MAPTR_QOS_CHILD");
  ASSERT_NE(want, nullptr) << "run by FastDdsDefaultProfilesFileReplacesTheShippedOne";
  Participant p("qos-override", private_options());
  EXPECT_EQ(p.writer(p.topic<msg::PlantTickPubSubType>(topic::kTick), Profile::kStream)->get_qos().history().depth,
            std::atoi(want));
}

/// A listener that never returns from an unmatch: it stands for a deletion that Fast DDS never
/// finishes (the deadlock of eProsima/Fast-DDS#6502 needs security and a remote participant
/// leaving at the wrong moment, which a test cannot arrange).
class StuckOnUnmatch : public eprosima::fastdds::dds::DataWriterListener,
                       public eprosima::fastdds::dds::DataReaderListener {
 public:
  void on_publication_matched(eprosima::fastdds::dds::DataWriter*,
                              const eprosima::fastdds::dds::PublicationMatchedStatus& s) override {
    if (s.current_count_change < 0) hang();
  }
  void on_subscription_matched(eprosima::fastdds::dds::DataReader*,
                               const eprosima::fastdds::dds::SubscriptionMatchedStatus& s) override {
    if (s.current_count_change < 0) hang();
  }

 private:
  [[noreturn]] static void hang() {
    for (;;) pause();
  }
};

TEST(ParticipantDeletion, ABoundedDeletionThatEndsInTimeLeavesNothingOpen) {
  bound_participant_deletion(30.0);
  {
    Participant p("bounded", private_options());
    p.writer(p.topic<msg::PlantTickPubSubType>(topic::kTick), Profile::kStream);
  }
  EXPECT_FALSE(participant_left_open());
}

TEST(ParticipantDeletion, ADeletionThatNeverEndsIsLeftAfterItsBound) {
  // In a fresh process (the one left open stays so): its destructor must return, and the
  // process must know, and end by _exit as the launcher does.
  const pid_t child = fork();
  if (child == 0) {
    execl("/proc/self/exe", "test_comm",
          "--gtest_filter=ParticipantDeletion.DISABLED_ChildLeavesAStuckDeletion",
          "--gtest_also_run_disabled_tests", static_cast<char*>(nullptr));
    _exit(127);
  }
  // Generous: the bound is 0.5 s; a deletion that is not bounded never ends at all.
  int st = 0;
  pid_t done = 0;
  for (int i = 0; i < 1200 && (done = waitpid(child, &st, WNOHANG)) == 0; ++i) usleep(100000);
  if (done == 0) {
    kill(child, SIGKILL);
    waitpid(child, &st, 0);
    FAIL() << "the participant's destructor did not return within 120 s";
  }
  ASSERT_TRUE(WIFEXITED(st)) << "signal " << (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
  EXPECT_EQ(WEXITSTATUS(st), 42) << "exit 43: the deletion was not known to be left open; else the child failed";
}

// Run only by the test above, in a fresh process: exits 42 when a deletion stuck in a listener
// was left after its bound and participant_left_open() says so.
TEST(ParticipantDeletion, DISABLED_ChildLeavesAStuckDeletion) {
  static StuckOnUnmatch stuck;  // outlives the participant left open
  bound_participant_deletion(0.5);
  {
    Participant p("stuck", private_options());
    auto* t = p.topic<msg::PlantTickPubSubType>(topic::kTick);
    p.writer(t, Profile::kStream, &stuck);
    p.reader(t, Profile::kStream, &stuck);
  }
  std::fflush(nullptr);
  _exit(participant_left_open() ? 42 : 43);
}

TEST(TickWire, APausedMemberFindsItselfInThePausedMask) {
  // Agents L0..L3, R0..R3, then group-L, group-R, central.
  EXPECT_EQ(paused_slot("L0", 4), 0);
  EXPECT_EQ(paused_slot("R2", 4), 6);
  EXPECT_EQ(paused_slot("group-L", 4), 8);
  EXPECT_EQ(paused_slot("group-R", 4), 9);
  EXPECT_EQ(paused_slot("central", 4), 10);
  EXPECT_EQ(paused_slot("L4", 4), -1);
  EXPECT_EQ(paused_slot("plant", 4), -1);
  msg::PlantTick t = two_sided_tick();
  EXPECT_TRUE(tick_valid(t, 4));  // no mask: nobody paused
  EXPECT_FALSE(paused_in(t, 6));
  std::vector<uint8_t> mask(11, 0);
  mask[6] = 1;
  t.paused(mask);
  EXPECT_TRUE(tick_valid(t, 4));
  EXPECT_TRUE(paused_in(t, 6));
  EXPECT_FALSE(paused_in(t, 0));
  EXPECT_FALSE(paused_in(t, -1));
  t.paused(std::vector<uint8_t>(10, 0));  // a mask of another fleet size
  EXPECT_FALSE(tick_valid(t, 4));
}

}  // namespace
}  // namespace maptr::comm
