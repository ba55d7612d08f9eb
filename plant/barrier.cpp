#include "plant/barrier.hpp"

namespace maptr::plant {

void Barrier::start(double now_s) { start_s_ = last_send_s_ = now_s; }

std::vector<MemberId> Barrier::expected(const Membership& m) {
  std::vector<MemberId> out;
  for (const auto& id : m.all())
    if (m.at(id).live) out.push_back(id);
  return out;
}

std::vector<MemberId> Barrier::late(const Membership& m) {
  std::vector<MemberId> out;
  for (const auto& id : m.all())
    if (m.at(id).live && !m.at(id).answered) out.push_back(id);
  return out;
}

bool Barrier::complete(const Membership& m) {
  for (const auto& id : m.all())
    if (m.at(id).live && !m.at(id).answered) return false;
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
