#pragma once
// What a fleet of `maptr soak` leaves behind once its launcher ended: processes that carry its
// fleet id, Fast DDS port files of its domain, shared-memory segments without an owner. Each
// check says what it found ("" for nothing) and removes it, so that the next fleet starts clean.
#include <sys/types.h>

#include <set>
#include <string>
#include <vector>

namespace maptr::deploy::cli {

/// PIDs of the running processes whose environment carries MAPTR_FLEET_ID=fleet_id.
std::vector<pid_t> pids_of_fleet(const std::string& fleet_id);

/// Adds the shared-memory segments mapped by the launcher `launcher` and by the processes of
/// the fleet it runs in `dir` (from its fleet.json) to `out`.
void sample_segments(pid_t launcher, const std::string& dir, std::set<std::string>& out);

/// Processes of the fleet of `run_dir` still there after a grace period ("" when none); they
/// are killed.
std::string check_leftovers(const std::string& run_dir);

/// Fast DDS port files in /dev/shm in the soak's domain's own port range. (Segments carry no
/// domain: other fleets on the machine make and leave them too; see check_segments.)
struct ShmCount {
  int ports = 0;
};
ShmCount count_shm(int domain);
/// "" unless the port files grew from `before` to `after`.
std::string check_shm(const ShmCount& before, const ShmCount& after);

/// The segments the fleet's processes mapped that are still in /dev/shm without an owner ("" when
/// none); they are removed.
std::string check_segments(const std::set<std::string>& own);

}  // namespace maptr::deploy::cli
