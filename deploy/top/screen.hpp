#pragma once
// The full-screen view of `maptr top` (ncurses): redraws the layout of the watched run a few
// times a second and at every resize, quits on `q` (or Ctrl-C), and keeps the final status on
// screen after the run ends.
#include "deploy/top/watch.hpp"

namespace maptr::top {

/// Redraws per second.
inline constexpr double kRefreshHz = 4.0;

/// Runs the view until `q`; returns the exit code (0).
int run_screen(Watch& w);

}  // namespace maptr::top
