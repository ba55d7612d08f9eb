#pragma once
// The middleware's floor of a lock-step tick, beside the pipes' (floor.hpp): a hub and W worker
// processes over Fast DDS with the fleet's own transport and QoS (shared memory for data, the
// lock-step topics' best-effort stream profile, the plant's SCHED_FIFO priority on the hub), and
// the fleet's own messages: in each round the hub writes one PlantTick sized for the fleet, every
// worker answers one AgentReply from its reader's listener, and the hub waits for all W answers
// as the plant does (one wake-up when the last arrives). No work, no checks, no files. A fleet
// tick over this floor's median ("x DDS floor") is what the project adds on top of Fast DDS.
#include <string>

namespace maptr::deploy {

/// The probe's figures (plain numbers: the probe's process hands them over in shared memory).
struct DdsFloorFigures {
  long rounds = 0;
  long resent = 0;  ///< rounds whose tick was written again (a best-effort sample lost)
  double median_us = 0.0, mean_us = 0.0, p99_us = 0.0;
  double cpu_us_per_round = 0.0;  ///< user + system CPU of hub and workers, µs
  double match_s = 0.0;           ///< from the start to every worker matched both ways
  double first_round_us = 0.0;    ///< the first round (its write opens every worker's port), µs
};

struct DdsFloorResult : DdsFloorFigures {
  bool measured = false;
  std::string problem;  ///< why not measured (workers not matched in time, ...)
  int workers = 0;
};

struct DdsFloorOptions {
  int workers = 1;
  int agents = 0;         ///< the fleet's N: the tick's per-side sequences are N/2 long (0: workers)
  int domain = 0;         ///< a domain no fleet uses at the time
  int hub_priority = 1;   ///< SCHED_FIFO of the hub's thread, as the plant's (0: normal scheduling)
  long rounds = 2000;
  long warmup = 200;
  double match_timeout_s = 30.0;  ///< per wave of workers
};

/// Forks the workers (before any DDS entity exists in this process), matches them and times the
/// rounds; never throws for a probe that cannot run: `measured` false and `problem` say why.
DdsFloorResult measure_dds_floor(const DdsFloorOptions& o);

}  // namespace maptr::deploy
