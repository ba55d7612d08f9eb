#pragma once
// Waypoint routes of a scenario (`type: waypoints`): the points as a file gives them, and the
// straights and arcs they are read as. Internal to config/.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "config/fields.hpp"

namespace maptr::config::detail {

/// Reads `points: [[x, y], ...]` (key "points" only; false for any other key) into g.points,
/// each a pair of finite numbers within 1e6 m; fails naming base.points[j].
bool read_points(const std::string& key, const YAML::Node& v, SegmentInput& g, const std::string& base,
                 const Context& c);

/// A waypoint route as straights and arcs: legs between the points (the route starts at (0, 0),
/// given or implied, heading along x), each corner rounded by an arc of corner_radius_m that
/// leaves the legs at tangent length rho tan(|turn| / 2). Fails naming the point: a repeated
/// point, a first leg that does not point ahead, a U-turn, legs too short for their corners.
std::vector<Segment> waypoint_segments(SegmentInput g, const std::string& base, const Context& c);

}  // namespace maptr::config::detail
