#pragma once
// A fleet launched in a child process of its own: the calling process never holds a DDS
// participant, so a fault inside Fast DDS ends one run, not the experiment or the bench, and no
// DDS state is carried from one fleet to the next. The child dies with its parent.
#include <atomic>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "config/scenario.hpp"

namespace maptr::deploy {

struct IsolatedLaunch {
  config::Scenario scenario;
  std::string run_dir;      ///< emptied and created
  std::string bin_dir;      ///< where maptr_plant & co. are
  int domain = 0;           ///< DDS domain id
  std::string output_file;  ///< the child's stdout and stderr go here ("": inherited)
};

/// Runs while the fleet runs, in a thread of the parent; `done` turns true when it has ended.
using LaunchWatcher = std::function<void(const std::atomic<bool>& done)>;

/// Runs the fleet in a forked child and returns its summary.json; a child that ended without
/// one gives {"status": "aborted: ..."} saying how it ended.
nlohmann::json launch_isolated(const IsolatedLaunch& l, const LaunchWatcher& watch = {});

/// Ctrl-C / SIGTERM from now on: the fleet running now ends (its launcher is sent SIGTERM) and
/// stop_requested() turns true, so that no further fleet starts.
void install_stop_handler();
bool stop_requested();

}  // namespace maptr::deploy
