#include "deploy/fleet/shm_cleanup.hpp"

#include <set>

#include "comm/dds/dds.hpp"
#include "comm/posix/shm_files.hpp"
#include "deploy/fleet/shm_segments.hpp"

namespace maptr::deploy::fleet {

namespace {
/// A segment's lock file younger than this may not be locked by its new owner yet, s.
constexpr double kSegmentMinAgeS = 2.0;
}  // namespace

void clean_shm_before_run(spdlog::logger& log) {
  if (const int stale = comm::clean_stale_shm(); stale > 0)
    log.info("removed {} unused Fast DDS shared-memory ports left in /dev/shm by earlier runs", stale);
}

void clean_shm_after_run(int domain, int highest_participant_id, int ds_port, spdlog::logger& log) {
  std::set<int> own = comm::rtps_ports(domain, highest_participant_id);
  own.insert(ds_port);
  if (const int removed = comm::clean_stale_shm(own); removed > 0)
    log.info("removed {} unused Fast DDS shared-memory ports from /dev/shm (this fleet's and older ones)",
             removed);
  // `fastdds shm clean` (above) also removes segments without owner, but it is a Python
  // program with a bounded wait: on a loaded machine it may be cut short.
  if (const auto gone = remove_orphan_segments("/dev/shm", kSegmentMinAgeS); !gone.empty())
    log.info("removed {} Fast DDS shared-memory segments without owner from /dev/shm", gone.size());
}

}  // namespace maptr::deploy::fleet
