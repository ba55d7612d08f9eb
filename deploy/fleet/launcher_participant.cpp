#include "deploy/fleet/launcher_participant.hpp"

#include "comm/lockstep/side.hpp"

namespace maptr::deploy::fleet {

namespace {
msg::NodeKind to_msg(ChildKind k) {
  switch (k) {
    case ChildKind::kAgent:
      return msg::NODE_AGENT;
    case ChildKind::kGroup:
      return msg::NODE_GROUP;
    case ChildKind::kCentral:
      return msg::NODE_CENTRAL;
    case ChildKind::kPlant:
      return msg::NODE_PLANT;
  }
  return msg::NODE_PLANT;
}
}  // namespace

LauncherParticipant::LauncherParticipant(const comm::DdsOptions& dds) {
  participant_ = std::make_unique<comm::Participant>("launcher", dds);
  auto& p = *participant_;
  p.reader(p.topic<msg::NodeReadyPubSubType>(comm::topic::kReady), comm::Profile::kLatched, &ready_);
  p.reader(p.topic<msg::PlantTickPubSubType>(comm::topic::kTick), comm::Profile::kStream, &ticks_);
  w_member_ =
      p.writer(p.topic<msg::MembershipEventPubSubType>(comm::topic::kMembership), comm::Profile::kLatched);
  w_control_ = p.writer(p.topic<msg::ControlPubSubType>(comm::topic::kControl), comm::Profile::kLatched);
  p.reader(p.topic<msg::FaultGatePubSubType>(comm::topic::kGate), comm::Profile::kLatched, &gates_);
}

LauncherParticipant::~LauncherParticipant() { participant_.reset(); }

void LauncherParticipant::wait_until(Clock::time_point until) { seen_ = signal_.wait_until(seen_, until); }

void LauncherParticipant::mark_seen() { seen_ = signal_.count(); }

long LauncherParticipant::undecodable() const {
  return static_cast<long>(ready_.undecodable() + ticks_.undecodable() + gates_.undecodable());
}

void LauncherParticipant::publish_member(const Child& c, msg::MemberEvent kind, double wall_s) {
  msg::MembershipEvent e;
  e.seq(++member_seq_);
  e.name(c.name);
  e.node_kind(to_msg(c.kind));
  e.side(comm::to_msg_side(c.side));
  e.index(c.index);
  e.kind(kind);
  e.wall_s(wall_s);
  e.participant_id(kind == msg::MEMBER_STARTED ? c.participant_id : -1);
  w_member_->write(&e);
}

void LauncherParticipant::start() {
  msg::Control c;
  c.command(msg::CONTROL_START);
  c.seq(1);
  w_control_->write(&c);
}

void LauncherParticipant::open_gate(uint64_t tick) {
  msg::Control c;
  c.command(msg::CONTROL_GATE_OPEN);
  c.seq(++control_seq_);
  c.tick(tick);
  c.member_seq(member_seq_);
  w_control_->write(&c);
}

}  // namespace maptr::deploy::fleet
