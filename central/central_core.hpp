#pragma once
// Central controller logic, free of DDS: the trajectory's body reference (v_x, w) at the next
// tick's time, turned into wheel references by the kinematics, and each group's active count
// relayed to the other group.
#include "config/scenario.hpp"

namespace maptr::central {

struct CentralOutput {
  double v_x_ref = 0.0, w_ref = 0.0;            ///< m/s, rad/s at t_{k+1}
  double phidot_ref_L = 0.0, phidot_ref_R = 0.0;  ///< rad/s
  int relay_for_L = 0, relay_for_R = 0;          ///< counts relayed to each group
  int segment = 0;
};

class CentralCore {
 public:
  explicit CentralCore(const config::Scenario& s) : s_(s) {}
  /// Command for tick k+1 given tick k's time and the groups' active counts seen at tick k.
  CentralOutput step(double t_k, int n_active_L, int n_active_R) const;

 private:
  config::Scenario s_;
};

}  // namespace maptr::central
