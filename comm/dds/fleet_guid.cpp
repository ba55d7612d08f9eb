#include "comm/dds/fleet_guid.hpp"

#include <unistd.h>

#include "comm/dds/security.hpp"

namespace maptr::comm {

namespace rtps = eprosima::fastrtps::rtps;

namespace {
constexpr rtps::octet kVendor[2] = {0x01, 0x0f};  // eProsima
void put_be32(rtps::octet* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<rtps::octet>(v >> (24 - 8 * i));
}
uint16_t host_id() {
  char name[256] = {0};
  gethostname(name, sizeof(name) - 1);
  uint32_t h = 2166136261u;  // FNV-1a
  for (const char* c = name; *c; ++c) h = (h ^ static_cast<unsigned char>(*c)) * 16777619u;
  return static_cast<uint16_t>(h ^ (h >> 16));
}
uint32_t get_be32(const rtps::octet* p) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = (v << 8) | p[i];
  return v;
}
}  // namespace

rtps::GuidPrefix_t fleet_guid_prefix(uint32_t fleet_id, int id) {
  rtps::GuidPrefix_t p;
  const uint16_t host = host_id();
  p.value[0] = kVendor[0];
  p.value[1] = kVendor[1];
  p.value[2] = static_cast<rtps::octet>(host >> 8);
  p.value[3] = static_cast<rtps::octet>(host & 0xff);
  put_be32(p.value + 4, static_cast<uint32_t>(id));
  put_be32(p.value + 8, fleet_id);
  return p;
}

std::optional<int> fleet_participant(uint32_t fleet_id, const rtps::InstanceHandle_t& writer) {
  const rtps::GUID_t guid = rtps::iHandle2GUID(writer);
  const rtps::octet* v = guid.guidPrefix.value;
  if (v[0] != kVendor[0] || v[1] != kVendor[1] || get_be32(v + 8) != fleet_id) return std::nullopt;
  return static_cast<int>(get_be32(v + 4));
}

bool written_by_id(uint32_t fleet_id, int agents, const rtps::InstanceHandle_t& writer, int base_id) {
  const rtps::GUID_t guid = rtps::iHandle2GUID(writer);
  // On a secure domain the prefix names the writer's certificate (comm/dds/security.hpp).
  if (is_secure_prefix(guid.guidPrefix)) {
    const auto secure = secure_base_id(guid.guidPrefix, agents);
    return secure && base_id >= 0 && *secure == base_id;
  }
  const auto id = fleet_participant(fleet_id, writer);
  return id && base_id >= 0 && *id % fleet_stride(agents) == base_id;
}

bool written_by(uint32_t fleet_id, int agents, const rtps::InstanceHandle_t& writer,
                const std::string& name) {
  return written_by_id(fleet_id, agents, writer, base_participant_id(name, agents));
}

std::string writer_process(uint32_t fleet_id, int agents, const rtps::InstanceHandle_t& writer) {
  const rtps::GUID_t guid = rtps::iHandle2GUID(writer);
  const auto id = is_secure_prefix(guid.guidPrefix) ? secure_base_id(guid.guidPrefix, agents)
                                                    : fleet_participant(fleet_id, writer);
  return id ? participant_name(*id, agents) : "";
}

std::string prefix_text(const rtps::InstanceHandle_t& writer) {
  static const char* hex = "0123456789abcdef";
  const rtps::GUID_t guid = rtps::iHandle2GUID(writer);
  std::string s;
  for (const auto b : guid.guidPrefix.value) s += {hex[b >> 4], hex[b & 15]};
  return s;
}

}  // namespace maptr::comm
