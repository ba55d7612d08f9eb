#include "plant/membership.hpp"

#include <algorithm>

#include "config/scenario.hpp"

namespace maptr::plant {

std::string member_name(const MemberId& id) {
  switch (id.role) {
    case Role::kAgent:
      return config::agent_name(id.side, id.index);
    case Role::kGroup:
      return id.side == 0 ? "group-L" : "group-R";
    case Role::kCentral:
      break;
  }
  return "central";
}

Membership::Membership(int per_side, std::function<double()> wall_ms)
    : per_side_(per_side), wall_ms_(std::move(wall_ms)) {
  for (int s = 0; s < 2; ++s) {
    agents_[s].assign(per_side, Member{});
    for (int j = 0; j < per_side; ++j) all_.push_back({Role::kAgent, s, j});
  }
  all_.push_back({Role::kGroup, 0, 0});
  all_.push_back({Role::kGroup, 1, 0});
  all_.push_back({Role::kCentral, 0, 0});
}

Member& Membership::at(const MemberId& id) {
  if (id.role == Role::kAgent) return agents_[id.side][id.index];
  if (id.role == Role::kGroup) return groups_[id.side];
  return central_;
}

const Member& Membership::at(const MemberId& id) const { return const_cast<Membership*>(this)->at(id); }

std::optional<MemberId> Membership::find(const std::string& name) const {
  int s = 0, j = 0;
  if (config::parse_agent_name(name, s, j) && j < per_side_) return MemberId{Role::kAgent, s, j};
  if (name == "group-L" || name == "group-R") return MemberId{Role::kGroup, name == "group-L" ? 0 : 1, 0};
  if (name == "central") return MemberId{Role::kCentral, 0, 0};
  return std::nullopt;
}

void Membership::begin_tick(const std::function<bool(int, int)>& excused) {
  for (const auto& id : all_) {
    Member& m = at(id);
    m.answered = false;
    m.excused = excused && id.role == Role::kAgent && !m.rejoining && excused(id.side, id.index);
  }
}

void Membership::record(const MemberId& id, const char* what) {
  records_.push_back({member_name(id), what, t_s_, wall_ms_()});
}

void Membership::mark_dead(const MemberId& id, const char* why) {
  Member& m = at(id);
  if (!m.live) return;
  m.live = false;
  record(id, why);
}

bool Membership::on_launcher(uint64_t seq, LauncherEvent kind, const std::string& name, int participant) {
  // The launcher numbers its events 1, 2, ...: one not above the last applied is no news, and
  // an unknown kind says nothing; neither moves the sequence a fault gate waits for.
  if (seq <= launcher_seq_ || kind == LauncherEvent::kOther) return false;
  launcher_seq_ = seq;
  const auto id = find(name);
  if (!id) return true;  // about the plant itself: only its number counts
  Member& m = at(*id);
  if (kind == LauncherEvent::kDied) {
    // A process killed while paused was already out: its death is still a change of its own.
    if (m.paused) record(*id, "died (launcher)");
    m.paused = false;
    mark_dead(*id, "died (launcher)");
    return true;
  }
  if (kind == LauncherEvent::kPaused) {
    m.paused = true;
    m.rejoining = false;
    m.live = false;
    record(*id, "paused (launcher)");
    return true;
  }
  // Started again, or resumed: waited for from now on; a resumed process keeps its writer.
  if (kind == LauncherEvent::kResumed && !m.paused) return true;
  record(*id, kind == LauncherEvent::kResumed ? "resumed (launcher)" : "started (launcher)");
  if (kind == LauncherEvent::kStarted) {
    m.writer_known = false;
    m.participant = participant > 0 ? participant : -1;  // 0 is the discovery server's: not said
  }
  m.paused = false;
  m.live = true;
  m.rejoining = true;
  return true;
}

void Membership::on_liveliness_lost(Role role, const WriterId& writer) {
  for (const auto& id : all_) {
    const Member& m = at(id);
    if (id.role == role && m.writer_known && m.writer == writer && !m.paused && !m.rejoining)
      mark_dead(id, "lost (DDS liveliness)");
  }
}

void Membership::on_answer(const MemberId& id, const WriterId& writer) {
  Member& m = at(id);
  if (m.paused) return;  // a reply sent before the pause, late: the member stays out
  if (!m.live || m.rejoining) record(id, "rejoined");
  m.live = true;
  m.rejoining = false;
  m.answered = true;
  m.writer = writer;
  m.writer_known = true;
}

int Membership::on_deadline() {
  int agents = 0;
  for (const auto& id : all_) {
    const Member& m = at(id);
    if (!m.live || m.answered || m.excused) continue;
    mark_dead(id, "missed the tick deadline");
    if (id.role == Role::kAgent) ++agents;
  }
  return agents;
}

std::vector<uint8_t> Membership::live_mask(int side) const {
  std::vector<uint8_t> m(per_side_);
  for (int j = 0; j < per_side_; ++j) m[j] = agents_[side][j].live ? 1 : 0;
  return m;
}

std::vector<uint8_t> Membership::paused_mask() const {
  std::vector<uint8_t> out;
  out.reserve(all_.size());
  for (const auto& id : all_) out.push_back(at(id).paused ? 1 : 0);
  return out;
}

int Membership::live_count(int side) const {
  int n = 0;
  for (const auto& m : agents_[side]) n += m.live ? 1 : 0;
  return n;
}

}  // namespace maptr::plant
