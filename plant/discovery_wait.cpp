#include "plant/discovery_wait.hpp"

#include <set>

#include "comm/dds/fleet_ids.hpp"
#include "config/scenario.hpp"

namespace maptr::plant {

namespace {

std::set<std::string> names_of(const std::vector<int>& ids, int agents) {
  std::set<std::string> out;
  for (int id : ids) out.insert(comm::participant_name(id, agents));
  return out;
}

/// "LABEL matched/expected", with the expected names not among the matched ones.
std::string part(const std::string& label, std::size_t matched, std::size_t expected,
                 const std::vector<std::string>& wanted, const std::set<std::string>& have, std::size_t max_names) {
  std::string s = label + " " + std::to_string(matched) + "/" + std::to_string(expected);
  std::vector<std::string> missing;
  for (const auto& w : wanted)
    if (!have.count(w)) missing.push_back(w);
  if (missing.empty()) return s;
  s += " (not matched: ";
  for (std::size_t i = 0; i < missing.size() && i < max_names; ++i) s += (i ? ", " : "") + missing[i];
  if (missing.size() > max_names) s += " and " + std::to_string(missing.size() - max_names) + " more";
  return s + ")";
}

std::vector<std::string> agent_names(int agents) {
  std::vector<std::string> out;
  const int per_side = agents / 2;
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < per_side; ++i) out.push_back(config::agent_name(side, i));
  return out;
}

}  // namespace

std::vector<std::string> discovery_unmatched(int agents, const DiscoveryView& v, std::size_t max_names) {
  const auto replies = names_of(v.reply_writers, agents), ticks = names_of(v.tick_readers, agents);
  const auto groups = names_of(v.group_writers, agents), centrals = names_of(v.central_writers, agents);
  std::vector<std::string> out;
  const auto check = [&](const std::string& name, const std::set<std::string>& writers) {
    if (out.size() < max_names && (!writers.count(name) || !ticks.count(name))) out.push_back(name);
  };
  for (const auto& a : agent_names(agents)) check(a, replies);
  for (const char* g : {"group-L", "group-R"}) check(g, groups);
  check("central", centrals);
  return out;
}

std::string discovery_wait_report(int agents, const DiscoveryView& v, std::size_t max_names) {
  const std::vector<std::string> agent_names = plant::agent_names(agents);
  std::vector<std::string> members = agent_names;
  for (const char* c : {"group-L", "group-R", "central"}) members.emplace_back(c);
  return part("agent replies", v.reply_writers.size(), static_cast<std::size_t>(agents), agent_names,
              names_of(v.reply_writers, agents), max_names) +
         ", " +
         part("group statuses", v.group_writers.size(), 2, {"group-L", "group-R"}, names_of(v.group_writers, agents),
              max_names) +
         ", " +
         part("central", v.central_writers.size(), 1, {"central"}, names_of(v.central_writers, agents), max_names) +
         ", " +
         part("tick readers", v.tick_readers.size(), static_cast<std::size_t>(v.tick_readers_expected), members,
              names_of(v.tick_readers, agents), max_names);
}

}  // namespace maptr::plant
