#pragma once
// run.mcap's recorder as a fleet runs it (recorder/recorder.hpp does the recording): its
// participant, with the launcher's id in the second id window (no process of the fleet ever has
// it), the lock-step writers it must have matched before the start, which of the fleet's agents
// it has not matched, and its counts at the end. The fleet decides what to do about the
// unmatched (start them again, wait, go on).
#include <spdlog/logger.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "comm/dds/dds.hpp"
#include "config/scenario.hpp"
#include "deploy/fleet/children.hpp"
#include "deploy/fleet/config.hpp"
#include "deploy/fleet/summary_build.hpp"
#include "recorder/recorder.hpp"

namespace maptr::deploy::fleet {

class FleetRecorder {
 public:
  /// Joins the domain of `dds` as the fleet's recorder and opens run.mcap in `run_dir`; records
  /// nothing (on() false) when the scenario's `record` is none.
  FleetRecorder(const config::Scenario& sc, const comm::DdsOptions& dds, const FleetConfig& cfg,
                const std::string& run_dir);

  bool on() const { return recorder_ != nullptr; }
  /// Its participant id (-1: none, or an id Fast DDS chooses).
  int participant_id() const { return participant_id_; }
  /// True once it has matched every lock-step writer (a tick writer, an answer writer per agent,
  /// two groups, central, the launcher's control and membership), or false at `until`.
  bool matched_lockstep(std::chrono::steady_clock::time_point until);
  /// The topics whose writers it lacks, after matched_lockstep() returned false.
  std::string missing() const { return recorder_->missing(); }
  /// How many agents' answer writers it has matched.
  std::size_t agents_matched() const;
  /// The running agents the launcher started whose answer writer it has not matched.
  std::vector<Child*> unrecorded(std::vector<Child>& kids) const;
  /// Ends the recording and puts its counts (recorded, dropped by verdict) into `rec`.
  void stop(RunRecord& rec, spdlog::logger& log);

 private:
  const config::Scenario& sc_;
  uint32_t fleet_id_;
  int participant_id_ = -1;
  std::unique_ptr<recorder::Recorder> recorder_;
};

}  // namespace maptr::deploy::fleet
