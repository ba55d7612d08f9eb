#include "deploy/fleet/shm_cleanup.hpp"

#include <set>

#include "comm/dds.hpp"
#include "comm/shm_files.hpp"

namespace maptr::deploy::fleet {

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
}

}  // namespace maptr::deploy::fleet
