#pragma once
// Fast DDS shared-memory segments in /dev/shm, which (unlike its ports) carry no domain or port
// number: `fastrtps_<16 characters>` holds a participant's buffers, `fastrtps_<id>_el` is its
// lock file, on which the owner holds a flock for the segment's whole life. A segment whose
// lock no process holds has lost its owner (a process killed by SIGKILL leaves it when no
// reader of its segment outlived it). Pure POSIX, no DDS.
#include <set>
#include <string>
#include <vector>

namespace maptr::deploy::fleet {

/// "fastrtps_0123456789abcdef" for a segment or its lock file name; "" for anything else
/// (ports, other files).
std::string segment_name(const std::string& file_name);

/// The segment a line of /proc/PID/maps maps ("" when none).
std::string segment_in_maps_line(const std::string& line);

/// The segments process `pid` maps (empty when it is gone or not readable).
std::set<std::string> segments_mapped_by(int pid);

/// True when `dir` holds the segment's lock file and no process holds its flock.
bool segment_orphaned(const std::string& dir, const std::string& name);

/// Removes every orphaned segment (both files) of this user in `dir` whose lock file is older
/// than min_age_s (a lock file just created is not locked yet), or of any age for the names
/// in `any_age`, and every empty segment file without lock file older than min_age_s (left by
/// a process killed while creating it); returns the names removed.
std::vector<std::string> remove_orphan_segments(const std::string& dir, double min_age_s,
                                                const std::set<std::string>& any_age = {});

}  // namespace maptr::deploy::fleet
