#include "control/path.hpp"

#include <algorithm>
#include <cmath>

namespace maptr::control {

namespace {
/// Below this |curvature| [1/m] a piece is a straight line.
constexpr double kStraight = 1e-12;
/// Two candidate points this close [m] count as equally near (the later one wins).
constexpr double kTie = 1e-12;

Projection projection_at(const Pose& robot, const Pose& on, double s, double kappa) {
  Projection p;
  p.on_path = on;
  p.s = s;
  p.kappa = kappa;
  const double dx = robot.x - on.x, dy = robot.y - on.y;
  p.cross_track = -dx * std::sin(on.theta) + dy * std::cos(on.theta);
  p.heading_error = wrap_angle(robot.theta - on.theta);
  p.distance = std::hypot(dx, dy);
  return p;
}
}  // namespace

double wrap_angle(double a) { return std::remainder(a, 2.0 * M_PI); }

Pose advance(const Pose& a, double kappa, double s) {
  if (std::fabs(kappa) < kStraight) return {a.x + s * std::cos(a.theta), a.y + s * std::sin(a.theta), a.theta};
  const double th = a.theta + kappa * s;
  return {a.x + (std::sin(th) - std::sin(a.theta)) / kappa, a.y - (std::cos(th) - std::cos(a.theta)) / kappa, th};
}

Path::Path(const Trajectory& tr) : accel_(tr.accel_mps2) {
  Pose at;
  double t = 0.0, s = 0.0;
  for (std::size_t i = 0; i < tr.segments.size(); ++i) {
    const Segment& g = tr.segments[i];
    Piece p;
    p.start = at;
    p.t0 = t;
    p.t1 = t + g.duration_s;
    p.s0 = s;
    p.v = g.speed_mps;
    p.ramp = i == 0 && accel_ > 0.0;
    p.w = g.yaw_rate_rad_s;
    if (p.v > 0.0) p.kappa = p.w / p.v;
    p.len = covered(p, g.duration_s);
    at = advance(at, p.kappa, p.len);
    if (p.v <= 0.0) at.theta += p.w * g.duration_s;
    t = p.t1;
    s += p.len;
    pieces_.push_back(p);
  }
}

double Path::covered(const Piece& p, double tau) const {
  if (p.v <= 0.0) return 0.0;
  if (!p.ramp) return p.v * tau;
  const double t_r = p.v / accel_;
  return tau < t_r ? 0.5 * accel_ * tau * tau : 0.5 * p.v * t_r + p.v * (tau - t_r);
}

double Path::speed(const Piece& p, double tau) const { return p.ramp ? std::min(p.v, accel_ * tau) : p.v; }

PathRef Path::at_time(double t) const {
  PathRef r;
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    const Piece& p = pieces_[i];
    if (t >= p.t1) continue;
    const double tau = std::max(0.0, t - p.t0);
    r.segment = static_cast<int>(i);
    r.s = p.s0 + covered(p, tau);
    r.pose = advance(p.start, p.kappa, covered(p, tau));
    if (p.v <= 0.0) r.pose.theta += p.w * tau;
    r.v = speed(p, tau);
    // The segment's own yaw rate at its speed, kappa v(t) under the ramp (the radius kept).
    r.w = r.v == p.v ? p.w : p.kappa * r.v;
    return r;
  }
  r.segment = static_cast<int>(pieces_.size());
  r.pose = end();
  r.s = length();
  return r;
}

Projection Path::project(const Pose& robot, double s_max) const {
  Projection best = projection_at(robot, Pose{}, 0.0, 0.0);
  bool found = false;
  auto consider = [&](const Piece& p, double sigma) {
    const Projection c = projection_at(robot, advance(p.start, p.kappa, sigma), p.s0 + sigma, p.kappa);
    if (!found || c.distance < best.distance - kTie || (c.distance <= best.distance + kTie && c.s >= best.s)) {
      best = c;
      found = true;
    }
  };
  for (const Piece& p : pieces_) {
    if (p.len <= 0.0 || p.s0 > s_max) continue;
    const double top = std::min(p.len, s_max - p.s0);
    consider(p, 0.0);
    consider(p, top);
    if (std::fabs(p.kappa) < kStraight) {
      const double along = (robot.x - p.start.x) * std::cos(p.start.theta) +
                           (robot.y - p.start.y) * std::sin(p.start.theta);
      consider(p, std::clamp(along, 0.0, top));
      continue;
    }
    const double cx = p.start.x - std::sin(p.start.theta) / p.kappa;
    const double cy = p.start.y + std::cos(p.start.theta) / p.kappa;
    const double d_phi =
        wrap_angle(std::atan2(robot.y - cy, robot.x - cx) - std::atan2(p.start.y - cy, p.start.x - cx));
    const int turns = static_cast<int>(std::ceil(std::fabs(p.kappa) * top / (2.0 * M_PI))) + 1;
    for (int k = -turns; k <= turns; ++k) {
      const double sigma = (d_phi + 2.0 * M_PI * k) / p.kappa;
      if (sigma > 0.0 && sigma < top) consider(p, sigma);
    }
  }
  return best;
}

double Path::length() const { return pieces_.empty() ? 0.0 : pieces_.back().s0 + pieces_.back().len; }

Pose Path::end() const {
  if (pieces_.empty()) return {};
  const Piece& p = pieces_.back();
  Pose e = advance(p.start, p.kappa, p.len);
  if (p.v <= 0.0) e.theta += p.w * (p.t1 - p.t0);
  return e;
}

void TrackingStats::add(double t, const Projection& p, const PathRef& ref, const Pose& robot) {
  final_err_ = std::hypot(robot.x - ref.pose.x, robot.y - ref.pose.y);
  if (t < settle_s_) return;
  const double ct = std::fabs(p.cross_track);
  if (ct > max_ct_) {
    max_ct_ = ct;
    max_ct_t_ = t;
  }
  sum_sq_ += ct * ct;
  ++n_;
  if (ref.v > 0.0) max_he_ = std::max(max_he_, std::fabs(p.heading_error));
}

double TrackingStats::cross_track_rms() const { return n_ > 0 ? std::sqrt(sum_sq_ / n_) : 0.0; }

}  // namespace maptr::control
