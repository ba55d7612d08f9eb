#pragma once
// A fleet launched in a child process of its own: the calling process never holds a DDS
// participant, so a fault inside Fast DDS ends one run, not the experiment or the bench, and no
// DDS state is carried from one fleet to the next. The child dies with its parent.
#include <atomic>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "deploy/fleet/launcher.hpp"

namespace maptr::deploy {

/// Runs while the fleet runs, in a thread of the parent; `done` turns true when it has ended.
using LaunchWatcher = std::function<void(const std::atomic<bool>& done)>;

/// Runs the fleet of `o` in a forked child and returns its summary.json; a child that ended
/// without one gives {"status": "aborted: ..."} saying how it ended. o.run_dir is emptied and
/// created; the child's stdout and stderr go to `output_file` ("": inherited).
nlohmann::json launch_isolated(const LaunchOptions& o, const std::string& output_file = "",
                               const LaunchWatcher& watch = {});

/// Ctrl-C / SIGTERM from now on: the fleet running now ends (its launcher is sent SIGTERM) and
/// stop_requested() turns true, so that no further fleet starts.
void install_stop_handler();
bool stop_requested();

}  // namespace maptr::deploy
