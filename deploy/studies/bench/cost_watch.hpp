#pragma once
// Watches a running fleet's processes (fleet.json) for their cost per tick: /proc counters of
// every process when trace.csv reaches the window's first tick (past discovery and warm-up)
// and again when it reaches its last, the tick of each read taken from trace.csv.
#include <atomic>
#include <string>

#include "deploy/studies/bench/fleet_cost.hpp"

namespace maptr::deploy {

/// The ticks a cost is measured over (as trace.csv numbers them).
struct TickWindow {
  long long start_tick = 0;
  long long end_tick = 0;
};

/// The window of a run of `ticks` ticks: from 20 % (past discovery and warm-up) to 90 % (before
/// the processes start to exit).
TickWindow cost_window(long long ticks);

/// Runs while the fleet runs (a launch watcher); `done` turns true when it has ended. If the run
/// ends before end_tick, the window ends at the last read taken while every process was alive.
FleetCost watch_fleet_cost(const std::string& run_dir, const TickWindow& w, const std::atomic<bool>& done);

/// The tick of trace.csv's last complete row, -1 when there is none yet.
long long last_trace_tick(const std::string& trace_path);

}  // namespace maptr::deploy
