#pragma once
// GUID prefix of a fleet participant (12 bytes), laid out as Fast DDS lays out its own so
// that its same-host and same-process tests keep working: the eProsima vendor id (2 bytes), a
// host id (2 bytes, from the host name), the participant id (4 bytes, big-endian: unique per
// process of the fleet) and the fleet id (a random 32-bit number the launcher draws per run,
// big-endian). A sample's writer handle holds its writer's GUID, so a reader can tell which
// process of its fleet wrote it. Without DDS Security any local process can forge a prefix:
// this keeps other fleets and careless tools out, not attackers (README, "What a local user
// can do"). On a secure domain (`maptr run --secure`) DDS Security replaces the prefix by one
// derived from the participant's certificate; written_by_id() then names the writer by its
// certificate (comm/dds/security.hpp).
#include <fastdds/rtps/common/InstanceHandle.h>

#include <cstdint>
#include <fastdds/rtps/common/GuidPrefix_t.hpp>
#include <optional>
#include <string>

#include "comm/dds/fleet_ids.hpp"

namespace maptr::comm {

/// GUID prefix of participant `id` of fleet `fleet_id`.
eprosima::fastrtps::rtps::GuidPrefix_t fleet_guid_prefix(uint32_t fleet_id, int id);

/// Participant id behind a writer handle, if that writer belongs to fleet `fleet_id`.
std::optional<int> fleet_participant(uint32_t fleet_id,
                                     const eprosima::fastrtps::rtps::InstanceHandle_t& writer);

/// True when `writer` belongs to the process whose first start had participant id `base_id`
/// (comm/dds/fleet_ids.hpp), in any of its starts. No strings: cheap enough for every sample.
bool written_by_id(uint32_t fleet_id, int agents, const eprosima::fastrtps::rtps::InstanceHandle_t& writer,
                   int base_id);

/// True when `writer` belongs to the process `name` of fleet `fleet_id` (any of its starts).
bool written_by(uint32_t fleet_id, int agents, const eprosima::fastrtps::rtps::InstanceHandle_t& writer,
                const std::string& name);

/// The process of fleet `fleet_id` (of `agents` agents) that `writer` belongs to ("plant",
/// "launcher", "L3", ...), by its GUID prefix or, on a secure domain, its certificate; "" for
/// a writer of no process of the fleet.
std::string writer_process(uint32_t fleet_id, int agents,
                           const eprosima::fastrtps::rtps::InstanceHandle_t& writer);

/// A writer's GUID prefix as 24 hexadecimal digits.
std::string prefix_text(const eprosima::fastrtps::rtps::InstanceHandle_t& writer);

}  // namespace maptr::comm
