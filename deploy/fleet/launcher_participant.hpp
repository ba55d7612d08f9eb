#pragma once
// The launcher's participant on the fleet's domain: readiness, the plant's ticks and its fault
// gates in; membership events and control commands out, each numbered here. The launcher's
// loops wait on it for the next sample.
#include <chrono>
#include <memory>
#include <utility>
#include <vector>

#include "comm/dds/dds.hpp"
#include "deploy/fleet/children.hpp"
#include "idl/maptrPubSubTypes.h"

namespace maptr::deploy::fleet {

class LauncherParticipant {
 public:
  using Clock = std::chrono::steady_clock;
  using Handle = eprosima::fastrtps::rtps::InstanceHandle_t;
  template <class T>
  using Samples = std::vector<std::pair<T, Handle>>;

  /// Joins the domain of `dds`: readers of readiness, ticks and gates; writers of membership and
  /// control (latched: a process that joins late gets them).
  explicit LauncherParticipant(const comm::DdsOptions& dds);
  ~LauncherParticipant();
  LauncherParticipant(const LauncherParticipant&) = delete;
  LauncherParticipant& operator=(const LauncherParticipant&) = delete;

  /// Waits until a sample arrives that the last wait did not see, or `until`.
  void wait_until(Clock::time_point until);
  /// What arrived so far counts as seen: the next wait waits for something newer.
  void mark_seen();

  /// What arrived since the last call, with each sample's writer.
  Samples<msg::NodeReady> take_ready() { return ready_.drain(); }
  Samples<msg::PlantTick> take_ticks() { return ticks_.drain(); }
  Samples<msg::FaultGate> take_gates() { return gates_.drain(); }
  /// Samples dropped so far because they did not deserialize, on all three topics.
  long undecodable() const;

  /// Publishes that `c` died, started, paused or resumed, `wall_s` after the launch.
  void publish_member(const Child& c, msg::MemberEvent kind, double wall_s);
  /// CONTROL_START: the run begins.
  void start();
  /// CONTROL_GATE_OPEN for the gate of `tick`, with the last membership event it follows.
  void open_gate(uint64_t tick);

  /// Leaves the domain (deletes the participant); what was counted stays readable.
  void leave() { participant_.reset(); }

 private:
  comm::Signal signal_;
  comm::Inbox<msg::NodeReady> ready_{signal_};
  comm::Inbox<msg::PlantTick> ticks_{signal_, comm::Wake::kNever};  // polled: no wake-up per tick
  comm::Inbox<msg::FaultGate> gates_{signal_};
  std::unique_ptr<comm::Participant> participant_;
  eprosima::fastdds::dds::DataWriter* w_member_ = nullptr;
  eprosima::fastdds::dds::DataWriter* w_control_ = nullptr;
  uint64_t seen_ = 0, member_seq_ = 0, control_seq_ = 1;
};

}  // namespace maptr::deploy::fleet
