#pragma once
// The lock-step barrier of one tick: tick k is complete when every live member (agents,
// groups, central) has answered it; a dead member is not waited for. Wall-clock times are
// passed in explicitly (s since any fixed origin): the barrier's deadline (after which the
// members still late are declared dead) and the resend interval for restarted members that
// may have matched the tick writer after tick k went out.
#include <vector>

#include "plant/membership.hpp"

namespace maptr::plant {

class Barrier {
 public:
  /// deadline_s: wall time a tick may take before its late members are declared dead, s;
  /// resend_s: interval of the resends to rejoining members, s.
  Barrier(double deadline_s, double resend_s) : deadline_s_(deadline_s), resend_s_(resend_s) {}

  /// Tick k went out at wall time now_s.
  void start(double now_s);
  /// Members that must answer the tick: the live ones.
  static std::vector<MemberId> expected(const Membership& m);
  /// Live members that have not answered yet.
  static std::vector<MemberId> late(const Membership& m);
  static bool complete(const Membership& m);
  /// Live members that have not answered yet, counted.
  static int late_count(const Membership& m);
  /// True when the tick must be sent again at now_s because answers are missing: none of the
  /// `answers` taken so far is newer than the repair interval (a sample lost on a best-effort
  /// transport; every follower answers a repeated tick again). Marks the send.
  bool repair_due(uint64_t answers, double now_s);
  /// The repair interval: `factor` times the typical barrier time, at least `min_s`.
  void set_repair(double typical_s, double factor, double min_s);
  /// True when the deadline of the tick has passed at now_s.
  bool deadline_passed(double now_s) const { return now_s - start_s_ > deadline_s_; }
  /// True when the tick must be sent again at now_s: a rejoining member has not answered and
  /// the last send is older than the resend interval. Marks the send.
  bool resend_due(const Membership& m, double now_s);

 private:
  double deadline_s_;
  double resend_s_;
  double start_s_ = 0.0;
  double last_send_s_ = 0.0;
  double repair_s_ = 0.1;
  uint64_t answers_ = 0;
  double progress_s_ = 0.0;
};

}  // namespace maptr::plant
