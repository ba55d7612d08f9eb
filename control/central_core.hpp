#pragma once
// Central controller: follows the mission's path in closed loop and turns the body command
// into wheel speed references by the skid-steer kinematics,
//   phidot_L = (v_x - (a/2) w) / r,  phidot_R = (v_x + (a/2) w) / r     [rad/s],
// and relays each group's active count to the other group. Pure: explicit time, no DDS.
//
// Path following (control/path.hpp gives the path, the reference and the nearest point): the
// speed is the mission's reference at t_{k+1}; the yaw rate is the path's curvature times that
// speed plus a heading loop towards a Stanley-style heading (Thrun et al., "Stanley: the robot
// that won the DARPA Grand Challenge", J. Field Robotics 23(9), 2006):
//   theta_d = theta_path - atan(e / L),   L = max(4 zeta^2 |v_x| / K, L_min)
//   w = v_ref kappa + clamp(K wrap(theta_d - theta), +-w_corr_max)
// e the signed cross-track error (> 0: the robot is left of the path), K the heading gain.
// Linearised about the path (e' = v e_theta, e_theta' = w - v kappa), the error obeys
// e'' + K e' + (K v / L) e = 0: with L = 4 zeta^2 v / K its damping ratio is zeta at every
// speed (zeta = 1, the default: critically damped, natural frequency K / 2). With no error the
// command is the mission's profile itself.
#include <utility>

#include "control/path.hpp"
#include "control/trajectory.hpp"
#include "control/tunable.hpp"

namespace maptr::control {

/// The scenario's control.* fields central reads, declared here and nowhere else: the member with
/// its default, and its row in central_tunables() (path, range, unit, description), which the
/// scenario's table takes as it is (control/tunable.hpp).
struct CentralTuning {
  double path_heading_gain_1_s = 2.0;      ///< K, 1/s
  double path_max_correction_rad_s = 1.0;  ///< w_corr_max, rad/s
  double path_damping = 1.0;               ///< zeta of the cross-track error, 1
};

inline std::vector<Tunable<CentralTuning>> central_tunables() {
  using T = CentralTuning;
  return {
      real_tunable<T>(
          "control.path_heading_gain_1_s", [](T& t) -> double& { return t.path_heading_gain_1_s; },
          Bounds::above(0, 1e3), "1/s",
          "central's path follower: heading gain K (the cross-track error settles critically damped at "
          "K/2 rad/s)"),
      real_tunable<T>(
          "control.path_max_correction_rad_s", [](T& t) -> double& { return t.path_max_correction_rad_s; },
          Bounds::above(0, 1e3), "rad/s",
          "central's path follower: the most yaw rate its heading loop adds to the path's own "
          "(curvature x speed) to bring the robot back to the path"),
      real_tunable<T>(
          "control.path_damping", [](T& t) -> double& { return t.path_damping; }, Bounds::above(0, 100), "1",
          "central's path follower: damping ratio of the cross-track error (look-ahead L = 4 zeta^2 v / K, "
          "at least L_min); 1: critically damped, below 1 it overshoots the path and settles sooner"),
  };
}

/// The tuning, the mission and what central knows of the robot and the run.
struct CentralConfig : CentralTuning {
  Trajectory trajectory;
  double dt_s = 0.01;             ///< tick period, s
  double track_m = 0.2;           ///< a, m
  double wheel_radius_m = 0.035;  ///< r, m
  double min_lookahead_m = 0.5;   ///< L_min, m
  double search_ahead_m = 2.0;    ///< the nearest point is sought up to the reference's length + this, m
};

/// The robot as central sees it in tick k.
struct CentralInput {
  double t_s = 0.0;       ///< t_k, s
  Pose pose;              ///< at t_k
  double v_x = 0.0;       ///< m/s, body speed at t_k
  int n_active_L = 0, n_active_R = 0;  ///< the groups' active counts seen at tick k
};

struct CentralOutput {
  double v_x_ref = 0.0, w_ref = 0.0;              ///< m/s, rad/s at t_{k+1}
  double phidot_ref_L = 0.0, phidot_ref_R = 0.0;  ///< rad/s
  int relay_for_L = 0, relay_for_R = 0;           ///< counts relayed to each group
  int segment = 0;                                ///< trajectory segment at t_{k+1}
  double cross_track_m = 0.0;                     ///< e at t_k, m
};

class CentralCore {
 public:
  explicit CentralCore(CentralConfig c) : c_(std::move(c)), path_(c_.trajectory) {}
  /// Command for tick k+1 given what tick k shows.
  CentralOutput step(const CentralInput& in) const;

 private:
  CentralConfig c_;
  Path path_;
};

}  // namespace maptr::control
