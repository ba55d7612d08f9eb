#include "config/waypoints.hpp"

#include <cmath>
#include <sstream>
#include <utility>

#include "model/params.hpp"

namespace maptr::config::detail {

/// points: [[x, y], ...], each a pair of finite numbers.
bool read_points(const std::string& key, const YAML::Node& v, SegmentInput& g, const std::string& base,
                 const Context& c) {
  if (key != "points") return false;
  const std::string path = base + ".points";
  if (!v.IsSequence() || v.size() < 2) c.fail(path, describe(v), "must be a list of at least two points [x, y]");
  for (std::size_t j = 0; j < v.size(); ++j) {
    const std::string here = path + "[" + std::to_string(j) + "]";
    if (!v[j].IsSequence() || v[j].size() != 2) c.fail(here, describe(v[j]), "must be a point [x, y] in metres");
    double xy[2] = {0.0, 0.0};
    for (int k = 0; k < 2; ++k) {
      try {
        xy[k] = v[j][k].as<double>();
      } catch (const YAML::Exception&) {
        c.fail(here, describe(v[j]), "must be a point [x, y] of numbers, in metres");
      }
      if (!std::isfinite(xy[k]) || std::fabs(xy[k]) > 1e6)
        c.fail(here, describe(v[j]), "coordinates must be finite, within 1e6 m");
    }
    g.points.emplace_back(xy[0], xy[1]);
  }
  return true;
}

/// A waypoint route as straights and arcs: legs between the points, each corner rounded by an
/// arc of corner_radius_m that leaves the legs at tangent length rho tan(|turn| / 2).
std::vector<Segment> waypoint_segments(SegmentInput g, const std::string& base, const Context& c) {
  const double v = g.seg.speed_mps, rho = g.corner_radius_m;
  if (g.points.empty()) c.fail(base + ".points", "(missing)", "a waypoint route needs its points");
  if (!(v > 0.0)) c.fail(base + ".speed_mps", model::param_value(v), "a waypoint route needs a speed above 0");
  if (g.has_duration || g.has_yaw_rate || g.has_radius)
    c.fail(base + (g.has_duration ? ".duration_s" : g.has_radius ? ".radius_m" : ".yaw_rate_rad_s"), "(given)",
           "a waypoint route takes its duration and turns from its points, speed and corner_radius_m");
  // The route starts at (0, 0): given as its first point, or implied.
  const bool implied = g.points.front() != std::make_pair(0.0, 0.0);
  if (implied) g.points.insert(g.points.begin(), {0.0, 0.0});
  auto name = [&](std::size_t j) {
    return base + ".points[" + std::to_string(implied ? j - 1 : j) + "]";
  };
  const std::size_t n = g.points.size();
  std::vector<double> len(n - 1), head(n - 1), tan_len(n, 0.0), turn(n, 0.0);
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const double dx = g.points[j + 1].first - g.points[j].first, dy = g.points[j + 1].second - g.points[j].second;
    len[j] = std::hypot(dx, dy);
    if (len[j] <= 1e-9) c.fail(name(j + 1), "(repeated)", "a point must differ from the one before it");
    head[j] = std::atan2(dy, dx);
  }
  if (std::fabs(head[0]) > 1e-9)
    c.fail(name(1), "(not ahead)",
           "the first leg must point ahead, along x (the robot starts heading along x in the segment's frame)");
  for (std::size_t j = 1; j + 1 < n; ++j) {
    turn[j] = std::remainder(head[j] - head[j - 1], 2.0 * M_PI);
    if (std::fabs(turn[j]) > M_PI - 1e-6) c.fail(name(j), "(a U-turn)", "the route turns back on itself here");
    tan_len[j] = rho * std::tan(0.5 * std::fabs(turn[j]));
  }
  std::vector<Segment> out;
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const double straight = len[j] - tan_len[j] - tan_len[j + 1];
    if (straight < -1e-9) {
      std::ostringstream why;
      why << "corner_radius_m = " << rho << " needs " << tan_len[j] + tan_len[j + 1] << " m of the leg from "
          << (j == 0 ? std::string("the start") : name(j).substr(base.size() + 1)) << " to this point; it is " << len[j] << " m (a smaller corner_radius_m, or points further apart)";
      c.fail(name(j + 1), "(too close)", why.str());
    }
    if (straight > 1e-9) out.push_back(Segment{"straight", v, 0.0, straight / v, name(j + 1)});
    if (j + 1 < n - 1 && std::fabs(turn[j + 1]) > 1e-12)
      out.push_back(Segment{"arc", v, std::copysign(v / rho, turn[j + 1]), rho * std::fabs(turn[j + 1]) / v,
                            base + ".corner_radius_m (the corner at " + name(j + 1).substr(base.size() + 1) + ")"});
  }
  return out;
}

}  // namespace maptr::config::detail
