#pragma once
// `maptr bench scale`, `tick` and `floor`: measurements of the distributed system itself and of
// the machine's IPC floor.
#include <string>
#include <vector>

namespace maptr::deploy {

struct BenchOptions {
  std::string what;  ///< "scale" | "tick" | "floor"
  std::vector<int> agents{4, 8, 16, 32, 64, 128, 256};
  std::vector<std::string> modes{"ec", "all"};  ///< scale: control modes, each at every size
  double duration_s = 30.0;                     ///< simulated seconds per run
  std::string out;                              ///< output folder
  std::string bin_dir, source_dir;
  int domain = 0;
  bool replot = false;    ///< scale: redraw scale.png from OUT/scale.csv, run nothing
  int hosts = 0;          ///< scale: also run each size on this many namespace hosts (0: one host only)
  bool ssh = false;       ///< scale: those hosts reached over ssh (the rehearsal of real machines)
  bool realtime = false;  ///< pace the fleets' ticks to the wall clock (every tick starts from idle)
  std::string record =
      "all";  ///< what each fleet records in run.mcap: all, plant or none (a run's default: all)
  std::vector<int> touch_kb{0, 128, 512};  ///< floor: KiB each worker touches per round
  std::string tick_filter = "auto";        ///< auto (a run's default: on in ec, off in all), true or false
  int plant_priority = -1;      ///< SCHED_FIFO priority of the plant's lock-step thread (-1: a run's default)
  double min_rtf = -1;          ///< scale: a size whose real-time factor is lower misses (-1: not checked)
  double max_floor_ratio = -1;  ///< scale: a size whose tick / floor is higher misses (-1: not checked)
  std::string junit;            ///< scale: JUnit XML written here, one case per size and mode ("": none)
};

int run_bench(const BenchOptions& o);

}  // namespace maptr::deploy
