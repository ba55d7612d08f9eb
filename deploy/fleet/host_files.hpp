#pragma once
// The run folder on hosts that share no disk with the launcher. Before anything starts there,
// the launcher ships what a host's processes read (the resolved scenario) into the host's own
// run folder, at the launcher's path, over the host's command prefix (ssh); each process writes
// its logs and files there. At the end the launcher copies each reachable host's folder back
// into RUN/hosts/NAME/ and merges it into its own run folder. A host whose run folder is the
// launcher's own (a shared disk: it sees the launcher's marker file) gets neither.
#include <string>
#include <utility>
#include <vector>

namespace maptr::deploy::fleet {

/// What a host's run folder is to the launcher.
enum class HostDisk {
  kSame,    ///< no command prefix: the launcher's machine
  kShared,  ///< the launcher's folder, seen through a shared disk
  kOwn,     ///< a folder of the host's own: shipped to and collected from
};

/// The launcher's marker file in its run folder: a host that sees it shares the disk.
inline constexpr const char* kLauncherMarker = ".maptr-launcher";

/// Prepares the run folder `run_dir` of the host reached through `prefix`: unless it sees the
/// marker, creates run_dir/logs and writes each of `files` (a path under run_dir, its content)
/// there. Sets `disk`; returns "" or why it could not.
std::string ship_run_files(const std::vector<std::string>& prefix, const std::string& run_dir,
                           const std::vector<std::pair<std::string, std::string>>& files, HostDisk& disk);

/// Copies the run folder of the host `name` reached through `prefix` (but the `shipped` files)
/// into run_dir/hosts/NAME/ and merges it into run_dir (merge_host_folder). Returns the line the
/// summary gives the host: "collected N files" or "not collected: why".
std::string collect_run_files(const std::vector<std::string>& prefix, const std::string& run_dir,
                              const std::string& name, const std::vector<std::string>& shipped);

/// Merges the folder `from` (a host's copy) into `run_dir`: a file run_dir lacks is copied; a
/// CSV file both have gets the copy's rows appended (its header left out: a process restarted
/// on another host continues its file), a log the copy's lines; any other file stays as it is.
/// Returns the number of files taken.
int merge_host_folder(const std::string& from, const std::string& run_dir);

}  // namespace maptr::deploy::fleet
