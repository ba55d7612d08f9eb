#include "deploy/fleet/fleet_recorder.hpp"

#include <algorithm>
#include <map>

#include "comm/dds/fleet_guid.hpp"
#include "comm/dds/fleet_ids.hpp"
#include "comm/posix/shm_files.hpp"
#include "records/compression.hpp"
#include "records/run_files.hpp"

namespace maptr::deploy::fleet {

FleetRecorder::FleetRecorder(const config::Scenario& sc, const comm::DdsOptions& dds, const FleetConfig& cfg,
                             const std::string& run_dir)
    : sc_(sc), fleet_id_(dds.fleet_id) {
  const auto scope = recorder::parse_scope(sc.record);
  if (scope == recorder::Scope::kNone) return;
  comm::DdsOptions o = dds;
  const int id = comm::fleet_stride(sc.robot.agents) + comm::kLauncherParticipantId;
  o.participant_id = id <= comm::rtps_max_participant_id(o.domain) ? id : -1;
  o.shm_port_queue = static_cast<uint32_t>(cfg.recorder_port_queue(sc.robot.agents));
  o.udp_receive_buffer_bytes = cfg.recorder_udp_buffer_bytes;
  participant_id_ = o.participant_id;
  recorder_ = std::make_unique<recorder::Recorder>(o, records::mcap_path(run_dir), scope, sc.robot.agents,
                                                   records::mcap_compression(sc.record_compression));
}

bool FleetRecorder::matched_lockstep(std::chrono::steady_clock::time_point until) {
  const int agents = sc_.robot.agents;
  const std::map<std::string, int> writers = {{comm::topic::kTick, 1},    {comm::topic::kAgentReply, agents},
                                              {comm::topic::kGroup, 2},   {comm::topic::kCentral, 1},
                                              {comm::topic::kControl, 1}, {comm::topic::kMembership, 1}};
  return recorder_->wait_matched(writers, until);
}

std::size_t FleetRecorder::agents_matched() const {
  return recorder_->matched_writers(comm::topic::kAgentReply).size();
}

std::vector<Child*> FleetRecorder::unrecorded(std::vector<Child>& kids) const {
  // written_by() names a writer by the fleet id in its GUID prefix, or on a secure domain by the
  // certificate that prefix was derived from (comm/dds/fleet_guid.hpp).
  const auto seen = recorder_->matched_writers(comm::topic::kAgentReply);
  std::vector<Child*> unseen;
  for (auto& c : kids) {
    if (c.kind != ChildKind::kAgent || c.external || !c.running) continue;
    const bool recorded = std::any_of(seen.begin(), seen.end(), [&](const auto& h) {
      return comm::written_by(fleet_id_, sc_.robot.agents, h, c.name);
    });
    if (!recorded) unseen.push_back(&c);
  }
  return unseen;
}

void FleetRecorder::stop(RunRecord& rec, spdlog::logger& log) {
  if (!recorder_) return;
  recorder_->stop();
  std::string counts;
  for (const auto& [topic, n] : recorder_->counts()) counts += " " + topic + " " + std::to_string(n);
  rec.recorded = recorder_->counts();
  rec.recorded_rejected = recorder_->rejected();
  std::string dropped;
  for (const auto& [kind, n] : rec.recorded_rejected) dropped += " " + kind + " " + std::to_string(n);
  log.info("recorded run.mcap:{}{}", counts,
           dropped.empty() ? "" : "; marked as dropped by the fleet:" + dropped);
}

}  // namespace maptr::deploy::fleet
