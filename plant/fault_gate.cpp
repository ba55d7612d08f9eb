#include "plant/fault_gate.hpp"

#include <algorithm>

namespace maptr::plant {

FaultGate::FaultGate(std::vector<double> fault_times_s, double timeout_s)
    : times_(std::move(fault_times_s)), timeout_s_(timeout_s) {
  std::sort(times_.begin(), times_.end());
  times_.erase(std::unique(times_.begin(), times_.end()), times_.end());
}

bool FaultGate::due(double t_s) {
  if (next_ >= times_.size() || t_s < times_[next_]) return false;
  while (next_ < times_.size() && t_s >= times_[next_]) ++next_;
  return true;
}

void FaultGate::hold(uint64_t tick) {
  tick_ = tick;
  open_ = false;
  need_seq_ = 0;
}

void FaultGate::on_open(uint64_t tick, uint64_t member_seq) {
  if (tick != tick_) return;
  open_ = true;
  need_seq_ = member_seq;
}

}  // namespace maptr::plant
