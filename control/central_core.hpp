#pragma once
// Central controller: the mission's body reference (v_x, w) at the next tick's time
// t_{k+1} = t_k + dt, turned into wheel speed references by the skid-steer kinematics,
//   phidot_L = (v_x - (a/2) w) / r,  phidot_R = (v_x + (a/2) w) / r     [rad/s],
// and each group's active count relayed to the other group. Pure: explicit time, no DDS.
#include <utility>

#include "control/trajectory.hpp"

namespace maptr::control {

struct CentralConfig {
  Trajectory trajectory;
  double dt_s = 0.01;             ///< tick period, s
  double track_m = 0.2;           ///< a, m
  double wheel_radius_m = 0.035;  ///< r, m
};

struct CentralOutput {
  double v_x_ref = 0.0, w_ref = 0.0;              ///< m/s, rad/s at t_{k+1}
  double phidot_ref_L = 0.0, phidot_ref_R = 0.0;  ///< rad/s
  int relay_for_L = 0, relay_for_R = 0;           ///< counts relayed to each group
  int segment = 0;                                ///< trajectory segment at t_{k+1}
};

class CentralCore {
 public:
  explicit CentralCore(CentralConfig c) : c_(std::move(c)) {}
  /// Command for tick k+1 given tick k's time [s] and the groups' active counts seen at tick k.
  CentralOutput step(double t_k, int n_active_L, int n_active_R) const;

 private:
  CentralConfig c_;
};

}  // namespace maptr::control
