#pragma once
// A fastddsgen PubSubType whose deserialize never throws. The generated code catches only a
// payload that is too short; fastcdr throws for others (a bad encapsulation header, a boolean
// other than 0 or 1), and Fast DDS calls deserialize inside DataReader::take, so such a sample
// from anyone on the domain would end the reading process. Here every refusal returns false,
// and last_deserialize_failed() tells the thread that called take that the sample it got is
// not a sample (Fast DDS still marks it as valid data).
#include <fastcdr/exceptions/Exception.h>
#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstring>
#include <string>

namespace maptr::comm {

/// Whether the last deserialize of a CheckedType on this thread refused its payload.
inline thread_local bool t_deserialize_failed = false;

inline bool last_deserialize_failed() { return t_deserialize_failed; }

template <class Generated>
class CheckedType : public Generated {
 public:
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    bool ok = false;
    try {
      ok = Generated::deserialize(payload, data);
    } catch (const eprosima::fastcdr::exception::Exception&) {
      ok = false;
    }
    t_deserialize_failed = !ok;
    return ok;
  }
};

/// Decodes `bytes` (a sample as sent: the CDR encapsulation header and body) as the fastddsgen
/// type `Generated` into `out`; false when the type refuses it. Never throws.
template <class Generated, class Message>
bool decode(const std::string& bytes, Message& out) {
  thread_local CheckedType<Generated> type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<uint32_t>(bytes.size()));
  if (!bytes.empty()) std::memcpy(payload.data, bytes.data(), bytes.size());
  payload.length = static_cast<uint32_t>(bytes.size());
  return type.deserialize(&payload, &out);
}

}  // namespace maptr::comm
