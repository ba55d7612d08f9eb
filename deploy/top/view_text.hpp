#pragma once
// The text of `maptr top`: lays a FleetView out in a terminal of `width` x `height` characters.
// The full-screen view draws these lines; `maptr top --once` prints them. One cell per agent
// ("L3   dead       0.0V  0.00A   12.3m") while every agent fits; otherwise one letter per agent
// and a count per state for each side (128 agents fit in 80 x 24).
#include <string>
#include <vector>

#include "deploy/top/fleet_view.hpp"

namespace maptr::top {

/// Characters of one agent cell in the detailed layout (36 of text and a gap).
inline constexpr int kCellWidth = 38;
/// Smallest terminal the view lays out in; below it one line says so.
inline constexpr int kMinWidth = 40, kMinHeight = 12;
/// Events the screen shows at most (as many as fit below the agents).
inline constexpr int kEventsShown = 4;

/// The screen as lines (each at most `width` characters). height <= 0: no height limit (every
/// agent gets a cell, every event a line). On a screen, the events shown end `events_back`
/// events before the latest (the list scrolled back; 0 the latest).
std::vector<std::string> layout(const FleetView& v, int width, int height, int events_back = 0);

/// The one-letter legend of the compact layout.
std::string legend();

}  // namespace maptr::top
