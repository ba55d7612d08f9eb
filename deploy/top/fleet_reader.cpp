#include "deploy/top/fleet_reader.hpp"

#include <unistd.h>

#include <chrono>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "comm/dds/fleet_guid.hpp"
#include "comm/posix/shm_files.hpp"
#include "comm/posix/udp_ports.hpp"
#include "config/scenario.hpp"
#include "idl/maptrPubSubTypes.h"
#include "records/fleet_file.hpp"
#include "records/run_files.hpp"

namespace maptr::top {

namespace dds = eprosima::fastdds::dds;
using Handle = eprosima::fastrtps::rtps::InstanceHandle_t;

namespace {

/// History depth for ticks and central's commands (only the newest is shown) and group statuses
/// (one per side).
constexpr int kTickDepth = 1, kCentralDepth = 1, kGroupDepth = 2;

/// A listener that takes every sample with the time it arrived and wakes the loop.
template <class T>
class TimedInbox : public dds::DataReaderListener {
 public:
  struct Item {
    T sample;
    double arrival_s;
    Handle writer;
    double written_s;  ///< the writer's source timestamp, s since the epoch
  };
  explicit TimedInbox(comm::Signal& s) : signal_(s) {}

  void on_data_available(dds::DataReader* reader) override {
    T sample;
    dds::SampleInfo info;
    bool any = false;
    while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      std::lock_guard<std::mutex> g(m_);
      q_.push_back({sample, steady_now_s(), info.publication_handle, info.source_timestamp.to_ns() * 1e-9});
      any = true;
    }
    if (any) signal_.notify();
  }
  std::vector<Item> drain() {
    std::lock_guard<std::mutex> g(m_);
    std::vector<Item> out;
    out.swap(q_);
    return out;
  }

 private:
  comm::Signal& signal_;
  std::mutex m_;
  std::vector<Item> q_;
};

dds::DataReaderQos watch_qos(int depth) {
  dds::DataReaderQos q = dds::DATAREADER_QOS_DEFAULT;
  q.reliability().kind = dds::BEST_EFFORT_RELIABILITY_QOS;
  q.durability().kind = dds::VOLATILE_DURABILITY_QOS;
  q.history().kind = dds::KEEP_LAST_HISTORY_QOS;
  q.history().depth = depth;
  q.resource_limits().max_samples = depth;
  q.resource_limits().max_instances = 1;
  q.resource_limits().max_samples_per_instance = depth;
  q.data_sharing().off();
  return q;
}

/// A participant id of `domain` whose unicast ports are free, searched from the highest id
/// down. Fast DDS would pick the lowest free id itself, but a fleet holds the lowest ids (and
/// a large one more than Fast DDS's 100 port mutations skip); its restarts move up one window of
/// ids at a time, so the top of the range is the last they reach.
int free_participant_id(int domain) {
  for (int id = comm::rtps_max_participant_id(domain); id > 0; --id)
    if (!comm::udp_port_listed(comm::rtps_metatraffic_unicast_port(domain, id)) &&
        !comm::udp_port_listed(comm::rtps_user_unicast_port(domain, id)))
      return id;
  throw std::runtime_error("no free DDS participant id on domain " + std::to_string(domain));
}

double system_now_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace

double steady_now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

FleetCoordinates read_fleet(const std::string& run_dir) {
  const records::FleetFile f = records::require_fleet_file(run_dir);
  if (!f.discovery_server)
    throw std::runtime_error(records::fleet_file_path(run_dir) +
                             ": no discovery server (the fleet has not started)");
  FleetCoordinates c;
  c.info.run_dir = run_dir;
  c.info.domain = f.domain;
  c.discovery_server = *f.discovery_server;
  c.discovery_own = f.discovery_own;
  c.lease_s = f.lease_s;
  c.fleet_id = static_cast<uint32_t>(f.fleet_id);
  c.launcher_pid = static_cast<int>(f.launcher_pid);
  const config::Scenario sc = config::load_scenario(f.config);
  c.info.scenario = sc.name;
  c.info.agents = sc.robot.agents;
  c.info.duration_s = sc.duration_s;
  return c;
}

struct FleetReader::Inboxes {
  explicit Inboxes(comm::Signal& s)
      : ticks(s), replies(s), groups(s), centrals(s), members(s), gates(s), ready(s) {}
  TimedInbox<msg::PlantTick> ticks;
  TimedInbox<msg::AgentReply> replies;
  TimedInbox<msg::GroupStatus> groups;
  TimedInbox<msg::CentralCommand> centrals;
  TimedInbox<msg::MembershipEvent> members;
  TimedInbox<msg::FaultGate> gates;
  TimedInbox<msg::NodeReady> ready;
};

FleetReader::FleetReader(const FleetCoordinates& c)
    : fleet_id_(c.fleet_id), joined_s_(system_now_s()), in_(std::make_unique<Inboxes>(signal_)) {
  comm::DdsOptions o;
  o.domain = c.info.domain;
  o.discovery_server = c.discovery_server;
  o.own_server = c.discovery_own;
  o.lease_s = c.lease_s;
  o.shm = false;
  o.participant_id = free_participant_id(o.domain);
  p_ = std::make_unique<comm::Participant>("maptr-top", o);
  auto& p = *p_;
  auto* sub = p.raw()->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
  if (!sub) throw std::runtime_error("cannot create the DDS subscriber of maptr top");
  const bool replay = c.info.replay_rate > 0;
  auto watch = [&](dds::Topic* t, int depth, dds::DataReaderListener* l) {
    if (replay)
      p.reader(t, comm::Profile::kReliableStream, l, depth);
    else if (!sub->create_datareader(t, watch_qos(depth), l, dds::StatusMask::data_available()))
      throw std::runtime_error("cannot create a reader on " + t->get_name());
  };
  watch(p.topic<msg::AgentReplyPubSubType>(comm::topic::kAgentReply), std::max(1, c.info.agents),
        &in_->replies);
  watch(p.topic<msg::GroupStatusPubSubType>(comm::topic::kGroup), kGroupDepth, &in_->groups);
  watch(p.topic<msg::CentralCommandPubSubType>(comm::topic::kCentral), kCentralDepth, &in_->centrals);
  p.reader(p.topic<msg::MembershipEventPubSubType>(comm::topic::kMembership), comm::Profile::kLatched,
           &in_->members);
  p.reader(p.topic<msg::FaultGatePubSubType>(comm::topic::kGate), comm::Profile::kLatched, &in_->gates);
  p.reader(p.topic<msg::NodeReadyPubSubType>(comm::topic::kReady), comm::Profile::kLatched, &in_->ready);
  // The tick reader last: a replay starts once its tick writer has matched this reader, and
  // discovery announces readers in the order they are created, so the others have matched too.
  watch(p.topic<msg::PlantTickPubSubType>(comm::topic::kTick), kTickDepth, &in_->ticks);
}

FleetReader::~FleetReader() { p_.reset(); }

void FleetReader::drain_into(FleetView& v) {
  auto ours = [&](const Handle& h) {
    return fleet_id_ == 0 || comm::fleet_participant(fleet_id_, h).has_value();
  };
  for (auto& x : in_->ready.drain())
    if (ours(x.writer)) v.on_ready(x.sample);
  for (auto& x : in_->members.drain())
    if (ours(x.writer)) v.on_membership(x.sample, x.written_s < joined_s_);
  for (auto& x : in_->gates.drain())
    if (ours(x.writer)) v.on_gate(x.sample);
  for (auto& x : in_->ticks.drain())
    if (ours(x.writer)) v.on_tick(x.sample, x.arrival_s);
  for (auto& x : in_->centrals.drain())
    if (ours(x.writer)) v.on_central(x.sample);
  for (auto& x : in_->groups.drain())
    if (ours(x.writer)) v.on_group(x.sample);
  for (auto& x : in_->replies.drain())
    if (ours(x.writer)) v.on_reply(x.sample, x.arrival_s);
}

}  // namespace maptr::top
