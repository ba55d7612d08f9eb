#include "plant/barrier.hpp"

#include <algorithm>

namespace maptr::plant {

namespace {
/// A member the tick still waits for: live, not answered, not excused.
bool waited(const Member& m) { return m.live && !m.answered && !m.excused; }
}  // namespace

void Barrier::start(double now_s) { start_s_ = last_send_s_ = progress_s_ = now_s; }

int Barrier::late_count(const Membership& m) {
  int n = 0;
  for (const auto& id : m.all()) n += waited(m.at(id));
  return n;
}

bool Barrier::repair_due(uint64_t answers, double now_s) {
  if (answers != answers_) {
    answers_ = answers;
    progress_s_ = now_s;
    return false;
  }
  if (now_s - progress_s_ <= repair_s_) return false;
  progress_s_ = now_s;
  return true;
}

void Barrier::set_repair(double typical_s, double factor, double min_s) {
  repair_s_ = std::max(min_s, factor * typical_s);
}

std::vector<MemberId> Barrier::expected(const Membership& m) {
  std::vector<MemberId> out;
  for (const auto& id : m.all())
    if (m.at(id).live) out.push_back(id);
  return out;
}

std::vector<MemberId> Barrier::late(const Membership& m) {
  std::vector<MemberId> out;
  for (const auto& id : m.all())
    if (waited(m.at(id))) out.push_back(id);
  return out;
}

bool Barrier::complete(const Membership& m) {
  for (const auto& id : m.all())
    if (waited(m.at(id))) return false;
  return true;
}

bool Barrier::resend_due(const Membership& m, double now_s) {
  bool rejoin_waits = false;
  for (const auto& id : m.all()) rejoin_waits |= m.at(id).rejoining && !m.at(id).answered;
  if (!rejoin_waits || now_s - last_send_s_ <= resend_s_) return false;
  last_send_s_ = now_s;
  return true;
}

}  // namespace maptr::plant
