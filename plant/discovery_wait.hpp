#pragma once
// What the plant still waits for before the fleet is matched: a line for the log when
// discovery makes no progress, naming the members whose endpoints the plant has not matched.
// Pure: the caller gives the participant ids (comm/dds/fleet_ids.hpp) behind its matched endpoints.
#include <string>
#include <vector>

namespace maptr::plant {

/// Participant ids behind the plant's matched endpoints (any start of a process counts).
struct DiscoveryView {
  std::vector<int> reply_writers;    ///< the agents' answers
  std::vector<int> group_writers;    ///< the groups' statuses
  std::vector<int> central_writers;  ///< central's commands
  std::vector<int> tick_readers;     ///< the tick's readers (members, the launcher, the recorder)
  int tick_readers_expected = 0;
};

/// "agent replies 127/128 (not matched: R78), group statuses 2/2, central 1/1, tick readers
/// 131/132 (not matched: R78)" for a fleet of `agents` agents; at most `max_names` names per
/// part, then "and K more".
std::string discovery_wait_report(int agents, const DiscoveryView& v, std::size_t max_names = 12);

/// The members (agents, then group-L, group-R, central) with an endpoint the plant has not
/// matched: a reply or status writer, or a tick reader; each once, at most `max_names`.
std::vector<std::string> discovery_unmatched(int agents, const DiscoveryView& v, std::size_t max_names);

}  // namespace maptr::plant
