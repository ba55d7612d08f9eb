#include "agent/agent_node.hpp"

#include <unistd.h>

#include "agent/agent_input.hpp"
#include "comm/lockstep/follower.hpp"
#include "comm/lockstep/side.hpp"
#include "config/core_configs.hpp"
#include "config/scenario.hpp"

namespace maptr::agent {

namespace {
msg::AgentState to_msg(control::AgentState s) {
  switch (s) {
    case control::AgentState::kIdle:
      return msg::AGENT_IDLE;
    case control::AgentState::kActive:
      return msg::AGENT_ACTIVE;
    case control::AgentState::kHolding:
      return msg::AGENT_HOLDING;
    case control::AgentState::kCoasting:
      return msg::AGENT_COASTING;
    case control::AgentState::kStopping:
      return msg::AGENT_STOPPING;
  }
  return msg::AGENT_IDLE;
}

/// The scenario's software faults and clears of agent `side`/`index`, at their ticks.
std::vector<MisbehaviourEvent> misbehaviours(const config::Scenario& s, int side, int index) {
  std::vector<MisbehaviourEvent> out;
  const std::string me = config::agent_name(side, index);
  for (const auto& f : s.faults) {
    if (f.target != me || !config::is_agent_fault_action(f.action)) continue;
    MisbehaviourEvent e;
    e.tick = config::first_tick_at(f.at_s, s.dt());
    e.value = f.value;
    if (f.action == "fault" && f.mode == "sensor") e.kind = Misbehaviour::kSensor;
    if (f.action == "fault" && f.mode == "erratic") e.kind = Misbehaviour::kErratic;
    if (f.action == "fault" && f.mode == "liar") e.kind = Misbehaviour::kLiar;
    out.push_back(e);  // a clear, or a motor fault: the software is healthy from then on
  }
  return out;
}
}  // namespace

AgentNode::AgentNode(const comm::ProcessArgs& args, int side, int index, std::shared_ptr<spdlog::logger> log)
    : args_(args), side_(side), index_(index), log_(std::move(log)), core_(config::agent_config(args.scenario), misbehaviours(args.scenario, side, index), side, index) {}

int AgentNode::run() {
  comm::TickFollower follower(args_, msg::NODE_AGENT, log_);
  follower.answer_writer<msg::AgentReplyPubSubType>(comm::topic::kAgentReply);
  long long last_tick = -2;  // the tick answered or skipped last
  const auto pid = static_cast<uint32_t>(getpid());
  return follower.run([&](const msg::PlantTick& t) {
    const control::AgentInput in = agent_input(t, side_, index_);
    const msg::SideTick& own = t.sides()[side_];
    const control::AgentOutput out = core_.step(in);
    msg::AgentReply rep;
    rep.tick(t.tick());
    rep.side(comm::to_msg_side(side_));
    rep.index(static_cast<uint16_t>(index_));
    rep.pid(pid);
    rep.voltage_V(out.voltage_V);
    rep.current_A(out.current_A);
    rep.efficiency(out.efficiency);
    rep.state(to_msg(out.state));
    rep.rejected(follower.rejected());
    // The plant waits for the agents whose wake bit is set (assigned, in their idle slot or
    // rejoining). The first tick of this process is answered in any case: a restarted agent may
    // take a tick before the plant knows it is back.
    const bool first = last_tick < 0;
    last_tick = in.tick;
    if (own.wake()[index_] != 0 || in.assigned || first) follower.answer(rep);
  });
}

}  // namespace maptr::agent
