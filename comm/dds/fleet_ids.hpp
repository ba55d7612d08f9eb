#pragma once
// Who is who in a fleet, from a DDS participant id alone (no DDS types here).
//
// Participant ids: 0 the discovery server, 1 the launcher, 2 the plant, 3 central, 4 group-L,
// 5 group-R, then agents L0..L(n-1), R0..R(n-1). A process restarted for the s-th time gets
// id base + (s mod windows) * stride, stride = n + 6, so fresh ports at every start; the name
// of id p is that of base p mod stride. comm/dds/fleet_guid.hpp turns an id into a GUID prefix.
#include <string>

namespace maptr::comm {

inline constexpr int kDiscoveryParticipantId = 0;
inline constexpr int kLauncherParticipantId = 1;
inline constexpr int kPlantParticipantId = 2;
inline constexpr int kCentralParticipantId = 3;
/// Participant id of the first start of group `side` (0 L, 1 R).
inline constexpr int group_participant_id(int side) { return 4 + side; }
/// Participant id of the first start of agent `index` of `side` in a fleet of `agents` agents.
inline constexpr int agent_participant_id(int side, int index, int agents) {
  return 6 + side * (agents / 2) + index;
}

/// Participant ids in one id window of a fleet of `agents` agents.
int fleet_stride(int agents);

/// Participant id of the first start of `name` ("plant", "central", "group-L", "L3", ...), or
/// -1 for a name that is not a process of such a fleet.
int base_participant_id(const std::string& name, int agents);

/// Process name of participant id `id` in a fleet of `agents` agents ("" if none).
std::string participant_name(int id, int agents);

}  // namespace maptr::comm
