#include "agent/agent_node.hpp"

#include <unistd.h>

#include "comm/follower.hpp"
#include "config/scenario.hpp"

namespace maptr::agent {

namespace {
static_assert(static_cast<uint8_t>(control::AgentState::kIdle) == msg::AGENT_IDLE &&
                  static_cast<uint8_t>(control::AgentState::kActive) == msg::AGENT_ACTIVE &&
                  static_cast<uint8_t>(control::AgentState::kHolding) == msg::AGENT_HOLDING &&
                  static_cast<uint8_t>(control::AgentState::kCoasting) == msg::AGENT_COASTING &&
                  static_cast<uint8_t>(control::AgentState::kStopping) == msg::AGENT_STOPPING,
              "the agent core's states are the message's");

control::AgentConfig make_config(const config::Scenario& s) {
  control::AgentConfig c;
  c.motor = s.robot.motor;
  c.pid = s.control.pid;
  c.wheel_radius_m = s.robot.wheel_radius_m;
  c.dt_s = s.dt();
  c.group_hold_s = s.control.group_hold_s;
  c.central_timeout_s = s.control.central_timeout_s;
  c.stop_decel_mps2 = s.control.stop_decel_mps2;
  return c;
}
}  // namespace

AgentNode::AgentNode(const comm::ProcessArgs& args, int side, int index, std::shared_ptr<spdlog::logger> log)
    : args_(args), side_(side), index_(index), log_(std::move(log)), core_(make_config(args.scenario)) {}

int AgentNode::run() {
  comm::TickFollower follower(args_, msg::NODE_AGENT, log_);
  auto* w_reply = follower.answer_writer<msg::AgentReplyPubSubType>(comm::topic::kAgentReply);
  return follower.run([&](const msg::PlantTick& t) {
    control::AgentInput in;
    in.tick = static_cast<long long>(t.tick());
    in.phidot_rad_s = side_ == 0 ? t.phidot_L() : t.phidot_R();
    in.battery_V = side_ == 0 ? t.battery_V_L() : t.battery_V_R();
    in.side_active_V = side_ == 0 ? t.V_active_L() : t.V_active_R();
    in.phidot_ref_rad_s = side_ == 0 ? t.phidot_ref_L() : t.phidot_ref_R();
    in.central_stamp = t.central_stamp();
    in.group_stamp = side_ == 0 ? t.group_stamp_L() : t.group_stamp_R();
    in.assigned = (side_ == 0 ? t.active_L() : t.active_R())[index_] != 0;
    const control::AgentOutput out = core_.step(in);
    msg::AgentReply rep;
    rep.tick(t.tick());
    rep.side(static_cast<uint8_t>(side_));
    rep.index(static_cast<uint16_t>(index_));
    rep.pid(static_cast<uint32_t>(getpid()));
    rep.voltage_V(out.voltage_V);
    rep.current_A(out.current_A);
    rep.efficiency(out.efficiency);
    rep.state(static_cast<uint8_t>(out.state));
    rep.rejected(follower.rejected());
    w_reply->write(&rep);
  });
}

}  // namespace maptr::agent
