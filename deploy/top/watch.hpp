#pragma once
// Follows one run for `maptr top`: waits until its lock-step runs (the plant has opened
// trace.csv, so discovery is over and the watcher cannot be mistaken for a member), joins it with
// a FleetReader, folds the samples into a FleetView and notices the end (the launcher's summary,
// or the launcher gone without one).
//
// A finished run is watched through a replay of its recording: the watch joins a private
// domain at once, starts `maptr replay` on it (a ReplayProcess) and follows it as live; the
// replay is over when the replayer has exited, which it does once every sample it sent was
// acknowledged, so the view then holds the recording's last tick.
#include <memory>
#include <optional>
#include <string>

#include "deploy/top/fleet_reader.hpp"
#include "deploy/top/fleet_view.hpp"
#include "deploy/top/replay_process.hpp"

namespace maptr::top {

/// True while the launcher of the run in `run_dir` is alive.
bool run_is_live(const std::string& run_dir);

/// How a finished run is replayed.
struct ReplayRequest {
  std::string maptr;  ///< the maptr executable that runs `maptr replay`
  int domain = 0;     ///< DDS domain of the replay (simple discovery)
  double rate = 1.0;  ///< X times the recorded pace
};

/// The coordinates of a replay of the finished run in `run_dir`: its scenario (fleet.json), the
/// domain of `r`, simple discovery and every writer accepted (fleet id 0). std::nullopt with
/// `why` set when the run has no recording (run.mcap) or no readable fleet.json.
std::optional<FleetCoordinates> replay_coordinates(const std::string& run_dir, const ReplayRequest& r,
                                                   std::string& why);

class Watch {
 public:
  /// Watches the live fleet at `c`.
  explicit Watch(FleetCoordinates c);
  /// Watches a replay: joins `c` (replay_coordinates) at once, then starts the replayer.
  Watch(FleetCoordinates c, const ReplayRequest& r);
  /// Joins once the lock-step runs, folds what arrived, reads the end of the run.
  void poll();
  /// Waits for a sample or at most `max_s`.
  void wait(double max_s);
  const FleetView& view() const { return view_; }
  bool joined() const { return reader_ != nullptr; }
  /// The run is over: final tick and summary, or the launcher gone (the replayer, for a replay).
  bool ended() const { return ended_; }
  bool replaying() const { return replay_ != nullptr; }
  /// A replay that ended badly: "maptr replay exited with code N"; "" otherwise.
  std::string replay_failure() const;
  /// The view has a tick, every live agent's reply and both groups' status (or they are dead).
  bool complete() const;

 private:
  /// Reads summary.json: the recorded final status, or the fleet gone without one.
  void end_run();

  FleetCoordinates c_;
  FleetView view_;
  std::unique_ptr<FleetReader> reader_;
  std::unique_ptr<ReplayProcess> replay_;  ///< after reader_: ended before the reader leaves
  bool ended_ = false;
};

}  // namespace maptr::top
