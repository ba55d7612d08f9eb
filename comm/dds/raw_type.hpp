#pragma once
// The fleet's topics as raw samples: a DDS type that carries a sample's serialized bytes (the
// 4-byte CDR encapsulation header and the CDR body) under the name of a MAPTR type, so that a
// recorder stores exactly what was sent and a replay sends it again; typed readers and writers
// of the fleet match it by type name.
#include <cstdint>
#include <fastdds/dds/topic/TopicDataType.hpp>
#include <string>
#include <vector>

#include "comm/dds/dds.hpp"

namespace maptr::comm {

/// A sample's serialized bytes, encapsulation header included.
struct RawSample {
  std::string bytes;
};

/// TopicDataType of RawSample under a MAPTR type name; `max_size` is the typed type's
/// preallocated payload size (longer samples are reallocated).
class RawType : public eprosima::fastdds::dds::TopicDataType {
 public:
  RawType(const std::string& type_name, uint32_t max_size);
  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override;
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override;
  std::function<uint32_t()> getSerializedSizeProvider(void* data) override;
  void* createData() override;
  void deleteData(void* data) override;
  bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle, bool force_md5) override;
};

/// One topic of the fleet: its name, its type's fully qualified name, the typed payload size,
/// its QoS profile and whether the plant publishes it.
struct FleetTopic {
  std::string topic, type_name;
  uint32_t max_size = 0;
  Profile profile = Profile::kStream;
  bool from_plant = false;
};

/// Every topic of the fleet (comm::topic), in a fixed order.
const std::vector<FleetTopic>& fleet_topics();

/// The topic named `topic` of the fleet, or nullptr.
const FleetTopic* find_fleet_topic(const std::string& topic);

/// The topics process `name` publishes ("plant", "central", "group-L", "launcher", "L3", ...;
/// none for any other name): what a secure domain's permissions grant it and what a recording
/// takes from its writers.
std::vector<std::string> published_topics(const std::string& name);

/// Whether process `name` publishes on `topic`.
bool publishes(const std::string& name, const std::string& topic);

}  // namespace maptr::comm
