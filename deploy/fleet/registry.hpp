#pragma once
// Running fleets, found wherever their run folder is. A launcher registers its fleet while it
// runs: one small JSON file per launcher in the registry folder ($XDG_RUNTIME_DIR/maptr/fleets,
// else /run/maptr/fleets as root, else /tmp/maptr-UID/fleets), removed when the fleet ends. A
// launcher killed with SIGKILL cannot remove its file: a reader takes an entry only while its
// launcher (pid and start time, against pid reuse) runs and its run folder's control FIFO is
// there, and removes the entries of launchers that are gone. `maptr ps` lists them; `top`,
// `kill`, `pause`, ... take the newest by default.
#include <string>
#include <vector>

#include "records/registry_entry.hpp"

namespace maptr::deploy::fleet {

/// One registered fleet (its file: records/registry_entry.hpp).
using FleetEntry = records::RegistryEntry;

/// The registry folder: from XDG_RUNTIME_DIR, the user id and `root` (pure: the caller passes
/// the environment).
std::string registry_dir(const char* xdg_runtime_dir, unsigned uid);
/// The registry folder of this process (its environment and user).
std::string registry_dir();

/// The start time of process `pid` (/proc/PID/stat field 22, clock ticks since boot); -1 when
/// it does not run.
long long process_start_ticks(int pid);

/// Registers this launcher's fleet for its lifetime (the file is removed by the destructor);
/// on the way, drops the entries of launchers that are gone.
class FleetRegistration {
 public:
  FleetRegistration(const std::string& run_dir, const std::string& scenario, int domain);
  ~FleetRegistration();
  FleetRegistration(const FleetRegistration&) = delete;
  FleetRegistration& operator=(const FleetRegistration&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// The running fleets, newest first; entries of launchers that are gone are removed.
std::vector<FleetEntry> running_fleets();

/// The simulated time a run folder's trace.csv has reached, s (NaN without one).
double trace_time_s(const std::string& run_dir);

}  // namespace maptr::deploy::fleet
