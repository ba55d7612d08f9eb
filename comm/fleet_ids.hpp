#pragma once
// Who is who in a fleet, from a DDS participant id or GUID prefix alone.
//
// Participant ids: 0 the discovery server, 1 the launcher, 2 the plant, 3 central, 4 group-L,
// 5 group-R, then agents L0..L(n-1), R0..R(n-1). A process restarted for the s-th time gets
// id base + (s mod windows) * stride, stride = n + 6, so fresh ports at every start; the name
// of id p is that of base p mod stride.
//
// GUID prefix of a fleet participant (12 bytes), laid out as Fast DDS lays out its own so
// that its same-host and same-process tests keep working: the eProsima vendor id (2 bytes), a
// host id (2 bytes, from the host name), the participant id (4 bytes, big-endian: unique per
// process of the fleet) and the fleet id (a random 32-bit number the launcher draws per run,
// big-endian). A sample's writer handle holds its writer's GUID, so a reader can tell which
// process of its fleet wrote it. Without DDS Security any local process can forge a prefix:
// this keeps other fleets and careless tools out, not attackers (README, "What a local user
// can do").
#include <fastdds/rtps/common/GuidPrefix_t.hpp>
#include <fastdds/rtps/common/InstanceHandle.h>

#include <cstdint>
#include <optional>
#include <string>

namespace maptr::comm {

inline constexpr int kDiscoveryParticipantId = 0;
inline constexpr int kLauncherParticipantId = 1;
inline constexpr int kPlantParticipantId = 2;

/// Participant ids in one id window of a fleet of `agents` agents.
int fleet_stride(int agents);

/// Participant id of the first start of `name` ("plant", "central", "group-L", "L3", ...), or
/// -1 for a name that is not a process of such a fleet.
int base_participant_id(const std::string& name, int agents);

/// Process name of participant id `id` in a fleet of `agents` agents ("" if none).
std::string participant_name(int id, int agents);

/// GUID prefix of participant `id` of fleet `fleet_id`.
eprosima::fastrtps::rtps::GuidPrefix_t fleet_guid_prefix(uint32_t fleet_id, int id);

/// Participant id behind a writer handle, if that writer belongs to fleet `fleet_id`.
std::optional<int> fleet_participant(uint32_t fleet_id, const eprosima::fastrtps::rtps::InstanceHandle_t& writer);

/// True when `writer` belongs to the process `name` of fleet `fleet_id` (any of its starts).
bool written_by(uint32_t fleet_id, int agents, const eprosima::fastrtps::rtps::InstanceHandle_t& writer,
                const std::string& name);

}  // namespace maptr::comm
