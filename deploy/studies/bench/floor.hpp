#pragma once
// The IPC floor of a lock-step tick on this machine, measured the same way the fleet ticks but
// with nothing else: a hub and W worker processes; in each round the hub writes 4 bytes to
// every worker's pipe, every worker answers 4 bytes on one shared pipe, and the hub waits for
// all W answers. No DDS, no work. A fleet tick is one such round through W = N + 3 processes
// (N agents, 2 groups, central), so its median over the floor's median ("x floor") says how
// much the fleet's machinery costs beyond the operating system's own wake-ups.
namespace maptr::deploy {

struct FloorResult {
  int workers = 0;
  int touch_kb = 0;                     ///< KiB each worker writes to (one byte per 64-byte line) per round
  long rounds = 0;                      ///< timed rounds (after warm-up)
  double median_us = 0.0;               ///< µs per round
  double p99_us = 0.0;                  ///< µs
  double ctx_switches_per_round = 0.0;  ///< voluntary + involuntary, hub and workers
  double cpu_us_per_round = 0.0;        ///< user + system CPU of hub and workers, µs
};

/// Runs `rounds` timed rounds after `warmup` untimed ones; throws std::runtime_error when a
/// pipe or a worker cannot be made. touch_kb > 0 gives each worker a working set: before each
/// answer it writes one byte in every 64-byte line of its own touch_kb KiB, as a process whose
/// tick touches that much memory (what `maptr bench floor` varies).
FloorResult measure_floor(int workers, long rounds = 2000, long warmup = 200, int touch_kb = 0);

}  // namespace maptr::deploy
