#pragma once
// Replay of a recording: every message of a run.mcap published again on a DDS domain, on its
// recorded topic with its recorded type name and the fleet's QoS profile for that topic, in the
// order recorded, paced by simulated time: each PlantTick goes out when the replay's wall clock
// reaches its time t divided by `rate` (the messages between two ticks follow the first at once). The bytes
// sent are the recorded CDR samples, so any reader of the fleet's types (maptr top, a test, a DDS tool) sees
// the run as if it were live. Samples the fleet dropped (a channel whose verdict is not "taken":
// recorder/recorder.hpp) are left out unless `with_rejected`; a recording whose channels carry no verdict is
// replayed whole.
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "comm/dds/dds.hpp"
#include "records/mcap.hpp"

namespace maptr::recorder {

struct ReplayOptions {
  double rate = 1.0;           ///< simulated seconds per wall second (> 0)
  double wait_reader_s = 5.0;  ///< before the first message, wait this long for a reader of the ticks
  double linger_s = 2.0;       ///< after the last, wait this long for readers to acknowledge
  bool with_rejected = false;  ///< also the samples the fleet dropped (forged, undecodable, malformed)
};

/// Whether the fleet took the samples of channel `ch` (its verdict is "taken", or it has none).
bool taken(const records::mcap::Channel& ch);

/// What a replay did.
struct ReplayResult {
  uint64_t messages = 0;
  uint64_t left_out = 0;   ///< messages the fleet dropped, not sent
  double wall_s = 0;       ///< from the first message to the last
  double recorded_s = 0;   ///< log time of the last message minus the first's
  double simulated_s = 0;  ///< simulated time of the last tick minus the first's
};

/// Publishes `file` on the domain of `o`; `progress` (if set) is called about once a second
/// with the messages sent so far; `stop` ends the replay early.
ReplayResult replay(const records::mcap::File& file, const comm::DdsOptions& o, const ReplayOptions& r,
                    const std::atomic<bool>& stop, const std::function<void(uint64_t)>& progress = {});

}  // namespace maptr::recorder
