#include "plant_core/fault_book.hpp"

#include <algorithm>

namespace maptr::plant_core {

namespace {
std::string agent(int side, int index) { return (side == 0 ? "L" : "R") + std::to_string(index); }
}  // namespace

FaultBook::FaultBook(int per_side, std::vector<AgentFaultEvent> events, double grace_s)
    : per_side_(per_side), grace_s_(grace_s), events_in_(std::move(events)) {
  std::stable_sort(events_in_.begin(), events_in_.end(), [](auto& a, auto& b) { return a.tick < b.tick; });
  for (int s = 0; s < 2; ++s) {
    motor_[s].assign(static_cast<std::size_t>(per_side), model::MotorFault{});
    open_[s].assign(static_cast<std::size_t>(per_side), -1);
    last_[s].assign(static_cast<std::size_t>(per_side), -1);
    flags_[s].assign(static_cast<std::size_t>(per_side), 0);
  }
}

void FaultBook::apply(long long k, double t_s) {
  for (; next_ < events_in_.size() && events_in_[next_].tick <= k; ++next_) {
    const AgentFaultEvent& e = events_in_[next_];
    if (e.side < 0 || e.side > 1 || e.index < 0 || e.index >= per_side_) continue;
    const auto j = static_cast<std::size_t>(e.index);
    int& open = open_[e.side][j];
    if (open >= 0)
      records_[static_cast<std::size_t>(open)].cleared_s = t_s;  // a new fault or a clear ends it
    open = -1;
    motor_[e.side][j] = model::MotorFault{};
    if (e.clear) continue;
    model::MotorFaultKind kind = model::MotorFaultKind::kNone;
    if (model::parse_motor_fault(e.mode, kind)) motor_[e.side][j] = {kind, e.value};
    AgentFaultRecord r;
    r.target = agent(e.side, e.index);
    r.mode = e.mode;
    r.value = e.value;
    r.injected_s = t_s;
    records_.push_back(r);
    open = last_[e.side][j] = static_cast<int>(records_.size()) - 1;
  }
}

bool FaultBook::any_motor_fault(int side) const {
  for (const auto& f : motor_[side])
    if (!f.healthy()) return true;
  return false;
}

bool FaultBook::disconnected(int side, int index) const {
  return flags_[side][static_cast<std::size_t>(index)] != 0;
}

void FaultBook::exposed(int side, int index) {
  const int open = open_[side][static_cast<std::size_t>(index)];
  if (open >= 0) ++records_[static_cast<std::size_t>(open)].exposed_ticks;
}

void FaultBook::on_flags(int side, const std::vector<uint8_t>& flags, double t_s, double dt_s,
                         const char* const* names, int n_names) {
  if (flags.size() != flags_[side].size()) return;  // a group without detection: none flagged
  for (std::size_t j = 0; j < flags.size(); ++j) {
    if (flags[j] == flags_[side][j]) continue;
    const bool raised = flags[j] != 0;
    flags_[side][j] = flags[j];
    DiagnosisEvent ev;
    ev.t_s = t_s;
    ev.target = agent(side, static_cast<int>(j));
    ev.diagnosed = raised && flags[j] < n_names ? names[flags[j]] : "";
    int open = open_[side][j];
    const int last = last_[side][j];
    if (raised && open < 0 && last >= 0) {  // just after a clear: still that fault's
      const auto& r = records_[static_cast<std::size_t>(last)];
      if (r.cleared_s && t_s - *r.cleared_s <= grace_s_ + 1e-9) open = last;
    }
    if (raised && open < 0) {
      ev.false_detection = true;
      ++false_;
    } else if (raised) {
      AgentFaultRecord& r = records_[static_cast<std::size_t>(open)];
      if (!r.detected_s) {
        r.detected_s = t_s;
        r.isolated_s = t_s + dt_s;
        r.diagnosed_mode = ev.diagnosed;
      } else {
        ++r.relapses;
      }
    } else if (last >= 0) {
      records_[static_cast<std::size_t>(last)].readmitted_s = t_s;
    }
    events_.push_back(ev);
  }
}

}  // namespace maptr::plant_core
