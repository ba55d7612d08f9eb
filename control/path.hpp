#pragma once
// The reference path of a trajectory, and where a robot stands against it. Pure geometry with
// explicit time: no DDS, no clock.
//
// Each segment of constant speed v [m/s] and yaw rate w [rad/s] lasting d [s] is a piece of
// path: a straight line (w = 0), an arc of curvature kappa = w / v [1/m], or, at v = 0, a turn in
// place (w != 0) or a stop (length 0). The robot starts at the origin heading along x. The
// reference travels the path at the segments' speeds; with a ramp limit a [m/s^2] the speed of
// the first segment is min(v, a t) and its yaw rate kappa v(t) (the arc's radius is kept).
//
// On an arc of curvature kappa from pose (x0, y0, theta0), at arc length s:
//   theta = theta0 + kappa s,  x = x0 + (sin theta - sin theta0) / kappa,
//   y = y0 - (cos theta - cos theta0) / kappa.
#include <vector>

#include "control/trajectory.hpp"

namespace maptr::control {

struct Pose {
  double x = 0.0;      ///< m, world
  double y = 0.0;      ///< m, world
  double theta = 0.0;  ///< rad
};

/// The reference at one instant.
struct PathRef {
  Pose pose;
  double v = 0.0;    ///< m/s, speed reference
  double w = 0.0;    ///< rad/s, yaw-rate reference (kappa v, or a turn in place's rate)
  double s = 0.0;    ///< m, path length travelled by the reference
  int segment = 0;   ///< segment index; segments.size() after the end
};

/// The point of the path nearest to a robot pose.
struct Projection {
  Pose on_path;               ///< nearest point, with the path's heading there
  double s = 0.0;             ///< m, its path length
  double kappa = 0.0;         ///< 1/m, curvature there
  double cross_track = 0.0;   ///< m, signed: > 0 when the robot is left of the path
  double heading_error = 0.0; ///< rad, robot heading minus the path's, in (-pi, pi]
  double distance = 0.0;      ///< m, |robot - nearest point|
};

/// Angle wrapped to (-pi, pi].
double wrap_angle(double a);

class Path {
 public:
  explicit Path(const Trajectory& t);

  /// The reference at simulated time t [s]; after the last segment: the end, stopped.
  PathRef at_time(double t) const;
  /// The nearest point of the path up to path length s_max [m] (the reference's length plus a
  /// margin: a robot is never judged against a part of the path it has not yet been sent to).
  /// Ties go to the later point.
  Projection project(const Pose& robot, double s_max) const;
  double length() const;  ///< m
  Pose end() const;       ///< the pose at the end of the path

 private:
  struct Piece {
    Pose start;
    double t0 = 0.0, t1 = 0.0;  ///< s, time span
    double s0 = 0.0, len = 0.0; ///< m
    double v = 0.0;             ///< m/s (segment speed)
    double kappa = 0.0;         ///< 1/m (moving pieces: w / v)
    double w = 0.0;             ///< rad/s, the segment's yaw rate
    bool ramp = false;          ///< the first segment under the ramp limit
  };
  std::vector<Piece> pieces_;
  double accel_ = 0.0;

  /// Path length a piece's reference has covered tau [s] after its start.
  double covered(const Piece& p, double tau) const;
  /// Speed of a piece's reference tau [s] after its start.
  double speed(const Piece& p, double tau) const;
};

/// The pose at arc length s along a piece of curvature kappa from `start`.
Pose advance(const Pose& start, double kappa, double s);

/// How well a run followed its path: the figures summary.json's `path` holds.
///   cross_track_max_m, cross_track_rms_m: |cross-track| after `settle_s` (the first second)
///   heading_error_max_rad: |heading error| after settle_s, while the reference moves
///   final_position_error_m: distance from the last pose to the reference's last pose
class TrackingStats {
 public:
  explicit TrackingStats(double settle_s = 1.0) : settle_s_(settle_s) {}
  /// One tick: the projection of the robot at time t [s] and the reference then.
  void add(double t, const Projection& p, const PathRef& ref, const Pose& robot);
  double cross_track_max() const { return max_ct_; }
  double cross_track_max_t() const { return max_ct_t_; }
  double cross_track_rms() const;
  double heading_error_max() const { return max_he_; }
  double final_position_error() const { return final_err_; }
  long long samples() const { return n_; }

 private:
  double settle_s_;
  double max_ct_ = 0.0, max_ct_t_ = 0.0, sum_sq_ = 0.0, max_he_ = 0.0, final_err_ = 0.0;
  long long n_ = 0;
};

}  // namespace maptr::control
