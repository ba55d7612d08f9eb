#pragma once
// Fast DDS shared-memory ports in /dev/shm around a fleet run: before it, the unused ones that
// earlier fleets left behind (same domain, same port numbers can keep this fleet from
// discovering itself); after it, this fleet's own ports whatever their age, with older ones,
// and the segments whose owner is gone (deploy/fleet/shm_segments.hpp).
#include <spdlog/logger.h>

namespace maptr::deploy::fleet {

void clean_shm_before_run(spdlog::logger& log);
/// highest_participant_id: the highest id any process of the fleet had; ds_port: the
/// discovery server's UDP port.
void clean_shm_after_run(int domain, int highest_participant_id, int ds_port, spdlog::logger& log);

}  // namespace maptr::deploy::fleet
