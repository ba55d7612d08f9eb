#include <gtest/gtest.h>

#include "comm/dds/fleet_ids.hpp"
#include "plant/discovery_wait.hpp"

using maptr::plant::discovery_wait_report;
using maptr::plant::DiscoveryView;

namespace {
constexpr int kAgents = 8;  // L0..L3, R0..R3
int agent(int side, int index) { return maptr::comm::agent_participant_id(side, index, kAgents); }
}  // namespace

TEST(DiscoveryWait, NamesTheMembersWhoseEndpointsAreNotMatched) {
  DiscoveryView v;
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < 4; ++i)
      if (!(side == 1 && i == 2)) v.reply_writers.push_back(agent(side, i));
  v.group_writers = {maptr::comm::group_participant_id(0), maptr::comm::group_participant_id(1)};
  v.central_writers = {};
  v.tick_readers = v.reply_writers;
  v.tick_readers.push_back(maptr::comm::kLauncherParticipantId);
  v.tick_readers_expected = kAgents + 4;
  EXPECT_EQ(discovery_wait_report(kAgents, v),
            "agent replies 7/8 (not matched: R2), group statuses 2/2, central 0/1 (not matched: central), "
            "tick readers 8/12 (not matched: R2, group-L, group-R, central)");
}

TEST(DiscoveryWait, ARestartedMemberCountsUnderItsNameAndLongListsAreCut) {
  DiscoveryView v;
  // L1's second start has the id one stride above its first.
  v.reply_writers = {agent(0, 1) + maptr::comm::fleet_stride(kAgents)};
  v.group_writers = {maptr::comm::group_participant_id(0), maptr::comm::group_participant_id(1)};
  v.central_writers = {maptr::comm::kCentralParticipantId};
  v.tick_readers_expected = 0;
  EXPECT_EQ(discovery_wait_report(kAgents, v, 3).substr(0, 66),
            "agent replies 1/8 (not matched: L0, L2, L3 and 4 more), group stat");
}

TEST(DiscoveryWait, TheUnmatchedMembersAreNamedOnceEachAndCut) {
  DiscoveryView v;
  // R2's answer is not matched, nor L1's tick reader, nor group-R's status; central is complete.
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < 4; ++i) {
      if (!(side == 1 && i == 2)) v.reply_writers.push_back(agent(side, i));
      if (!(side == 0 && i == 1)) v.tick_readers.push_back(agent(side, i));
    }
  v.group_writers = {maptr::comm::group_participant_id(0)};
  v.central_writers = {maptr::comm::kCentralParticipantId};
  for (int id : {maptr::comm::group_participant_id(0), maptr::comm::group_participant_id(1),
                 maptr::comm::kCentralParticipantId})
    v.tick_readers.push_back(id);
  using maptr::plant::discovery_unmatched;
  EXPECT_EQ(discovery_unmatched(kAgents, v, 64), (std::vector<std::string>{"L1", "R2", "group-R"}));
  EXPECT_EQ(discovery_unmatched(kAgents, v, 2), (std::vector<std::string>{"L1", "R2"}));
  v.group_writers.push_back(maptr::comm::group_participant_id(1));
  v.reply_writers.push_back(agent(1, 2));
  v.tick_readers.push_back(agent(0, 1));
  EXPECT_TRUE(discovery_unmatched(kAgents, v, 64).empty());
}
