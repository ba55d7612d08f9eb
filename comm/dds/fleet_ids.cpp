#include "comm/dds/fleet_ids.hpp"

#include "config/scenario.hpp"

namespace maptr::comm {

namespace {
constexpr int kFirstAgentId = 6;
const char* const kControllers[] = {"plant", "central", "group-L", "group-R"};
}  // namespace

int fleet_stride(int agents) { return kFirstAgentId + agents; }

int base_participant_id(const std::string& name, int agents) {
  for (int i = 0; i < 4; ++i)
    if (name == kControllers[i]) return kPlantParticipantId + i;
  int side = 0, index = 0;
  const int per_side = agents / 2;
  if (config::parse_agent_name(name, side, index) && index < per_side)
    return agent_participant_id(side, index, agents);
  return -1;
}

std::string participant_name(int id, int agents) {
  if (id < 0 || agents <= 0) return "";
  const int base = id % fleet_stride(agents);
  if (base == kDiscoveryParticipantId) return "discovery";
  if (base == kLauncherParticipantId) return "launcher";
  if (base < kFirstAgentId) return kControllers[base - kPlantParticipantId];
  const int per_side = agents / 2;
  return config::agent_name((base - kFirstAgentId) / per_side, (base - kFirstAgentId) % per_side);
}

}  // namespace maptr::comm
