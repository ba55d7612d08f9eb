#pragma once
// Memory of a running fleet: the proportional set size (shared pages split among their users)
// of every process fleet.json names, sampled once the lock-step is under way.
#include <atomic>
#include <string>
#include <vector>

namespace maptr::deploy {

struct FleetMemory {
  std::vector<long> agent_pss_kB;  ///< one per agent process
  long total_pss_kB = 0;           ///< every process of the fleet and the launcher
};

/// Waits until RUN_DIR/trace.csv shows the run under way (or `done`), then samples once.
FleetMemory sample_memory(const std::string& run_dir, const std::atomic<bool>& done);

/// CPU seconds (user + system) of this process (RUSAGE_SELF) or its waited-for children.
double cpu_seconds(int who);

double median(std::vector<long> v);

}  // namespace maptr::deploy
