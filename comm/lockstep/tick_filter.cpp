#include "comm/lockstep/tick_filter.hpp"

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>

#include <atomic>
#include <cstdlib>
#include <fastdds/dds/topic/IContentFilter.hpp>
#include <fastdds/dds/topic/IContentFilterFactory.hpp>
#include <mutex>
#include <stdexcept>
#include <string>

#include "comm/lockstep/tick_check.hpp"
#include "idl/maptr.h"

namespace maptr::comm {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

namespace {

/// The last tick decoded, shared by every filter of one participant: the plant's writer
/// evaluates one filter per agent for the same sample, one after the other, and decodes it once.
class DecodedTick {
 public:
  /// Calls use(tick) with the decoded sample, or returns false when it does not decode.
  template <class F>
  bool with(const dds::IContentFilter::SerializedPayload& payload,
            const dds::IContentFilter::FilterSampleInfo& info, F&& use) {
    std::lock_guard<std::mutex> lock(m_);
    const auto& id = info.sample_identity;
    // A reader may get no identity with the sample: then the cache is not used.
    const bool keyed = id.writer_guid() != eprosima::fastrtps::rtps::GUID_t::unknown();
    if (!keyed || !(valid_ && id == key_)) {
      valid_ = decode(payload);
      key_ = keyed ? id : eprosima::fastrtps::rtps::SampleIdentity::unknown();
    }
    if (!valid_) return false;
    use(tick_);
    return true;
  }

 private:
  std::mutex m_;
  msg::PlantTick tick_;
  eprosima::fastrtps::rtps::SampleIdentity key_ = eprosima::fastrtps::rtps::SampleIdentity::unknown();
  bool valid_ = false;

  bool decode(const dds::IContentFilter::SerializedPayload& payload) {
    if (payload.data == nullptr || payload.length == 0) return false;
    try {
      eprosima::fastcdr::FastBuffer buf(reinterpret_cast<char*>(payload.data), payload.length);
      eprosima::fastcdr::Cdr cdr(buf, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN,
                                 eprosima::fastcdr::Cdr::DDS_CDR);
      cdr.read_encapsulation();
      tick_.deserialize(cdr);
      return true;
    } catch (...) {
      return false;
    }
  }
};

class TickFilter final : public dds::IContentFilter {
 public:
  TickFilter(DecodedTick& cache, int side, int index) : cache_(cache), side_(side), index_(index) {}

  bool evaluate(const SerializedPayload& payload, const FilterSampleInfo& info,
                const GUID_t&) const override {
    bool wakes = true;
    // A tick that does not decode goes through: the follower's checks reject it and count it.
    cache_.with(payload, info, [&](const msg::PlantTick& t) { wakes = tick_wakes_agent(t, side_, index_); });
    return wakes;
  }

  void set(int side, int index) {
    side_ = side;
    index_ = index;
  }

 private:
  DecodedTick& cache_;
  int side_;
  int index_;
};

bool parse_int(const char* s, int lo, int hi, int& out) {
  if (s == nullptr || *s == '\0') return false;
  char* end = nullptr;
  const long v = std::strtol(s, &end, 10);
  if (*end != '\0' || v < lo || v > hi) return false;
  out = static_cast<int>(v);
  return true;
}

class TickFilterFactory : public dds::IContentFilterFactory {
 public:
  ReturnCode_t create_content_filter(const char*, const char*, const eprosima::fastdds::dds::TopicDataType*,
                                     const char*, const ParameterSeq& params,
                                     dds::IContentFilter*& instance) override {
    if (instance != nullptr) {  // new parameters for a filter in place: no table change
      int side = 0, index = 0;
      if (params.length() != 2 || !parse_int(params[0], 0, 1, side) || !parse_int(params[1], 0, 65535, index))
        return ReturnCode_t::RETCODE_BAD_PARAMETER;
      static_cast<TickFilter*>(instance)->set(side, index);
      return ReturnCode_t::RETCODE_OK;
    }
    // On the writer's side a new filter enters the writer's table next (TickFilterGate).
    if (auto* g = gate_.load()) g->mutation_begins();
    // Parameters: side (0 or 1), index within the side.
    int side = 0, index = 0;
    if (params.length() != 2 || !parse_int(params[0], 0, 1, side) || !parse_int(params[1], 0, 65535, index))
      return ReturnCode_t::RETCODE_BAD_PARAMETER;
    instance = new TickFilter(cache_, side, index);
    return ReturnCode_t::RETCODE_OK;
  }

  ReturnCode_t delete_content_filter(const char*, dds::IContentFilter* instance) override {
    // On the writer's side the filter leaves the writer's table next (TickFilterGate).
    if (auto* g = gate_.load()) g->mutation_begins();
    delete static_cast<TickFilter*>(instance);
    return ReturnCode_t::RETCODE_OK;
  }

  void set_gate(TickFilterGate* g) { gate_.store(g); }

 private:
  DecodedTick cache_;
  std::atomic<TickFilterGate*> gate_{nullptr};
};

}  // namespace

void TickFilterGate::mutation_begins() {
  std::unique_lock<std::mutex> lk(m_);
  // Bounded, so that a write that never ends cannot hold discovery for good.
  cv_.wait_for(lk, std::chrono::seconds(2), [this] { return !writing_; });
  ++pending_;
}

void TickFilterGate::matched_changed() {
  std::lock_guard<std::mutex> g(m_);
  if (pending_ > 0) --pending_;
  cv_.notify_all();
}

void register_tick_filter(dds::DomainParticipant* dp, TickFilterGate* gate) {
  // One factory for the process, never deleted: a participant may call it until it is gone.
  static auto* const factory = new TickFilterFactory();
  if (gate) factory->set_gate(gate);
  if (dp->lookup_content_filter_factory(kTickFilterClass) != nullptr) return;
  if (dp->register_content_filter_factory(kTickFilterClass, factory) != ReturnCode_t::RETCODE_OK)
    throw std::runtime_error("cannot register the tick filter");
}

dds::ContentFilteredTopic* agent_tick_topic(dds::DomainParticipant* dp, dds::Topic* tick, int side,
                                            int index) {
  register_tick_filter(dp);
  const std::string name =
      std::string(tick->get_name()) + "/agent/" + std::to_string(side) + "/" + std::to_string(index);
  auto* cft = dp->create_contentfilteredtopic(
      name, tick, "wake(%0, %1)", {std::to_string(side), std::to_string(index)}, kTickFilterClass);
  if (cft == nullptr) throw std::runtime_error("cannot create the filtered tick topic " + name);
  return cft;
}

}  // namespace maptr::comm
