#pragma once
// Follows one run for `maptr top`: waits until its lock-step runs (the plant has opened
// trace.csv, so discovery is over and the watcher cannot be mistaken for a member), joins it with
// a FleetReader, folds the samples into a FleetView and notices the end (the launcher's summary,
// or the launcher gone without one).
#include <memory>
#include <optional>
#include <string>

#include "deploy/top/fleet_reader.hpp"
#include "deploy/top/fleet_view.hpp"

namespace maptr::top {

/// True while the launcher of the run in `run_dir` is alive.
bool run_is_live(const std::string& run_dir);

/// Watching a finished run replays its recording on a private DDS domain (`maptr replay`) and
/// returns the coordinates to join. This build records no runs: it returns std::nullopt and
/// sets `why`.
std::optional<FleetCoordinates> start_replay(const std::string& run_dir, std::string& why);

class Watch {
 public:
  explicit Watch(FleetCoordinates c);
  /// Joins once the lock-step runs, folds what arrived, reads the end of the run.
  void poll();
  /// Waits for a sample or at most `max_s`.
  void wait(double max_s);
  const FleetView& view() const { return view_; }
  bool joined() const { return reader_ != nullptr; }
  /// The run is over: final tick and summary, or the launcher gone.
  bool ended() const { return ended_; }
  /// The view has a tick, every live agent's reply and both groups' status (or they are dead).
  bool complete() const;

 private:
  FleetCoordinates c_;
  FleetView view_;
  std::unique_ptr<FleetReader> reader_;
  bool ended_ = false;
};

}  // namespace maptr::top
