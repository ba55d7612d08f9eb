#include "central/central_node.hpp"

#include "comm/lockstep/follower.hpp"
#include "config/core_configs.hpp"

namespace maptr::central {

CentralNode::CentralNode(const comm::ProcessArgs& args, std::shared_ptr<spdlog::logger> log)
    : args_(args), log_(std::move(log)), core_(config::central_config(args.scenario)) {}

int CentralNode::run() {
  comm::TickFollower follower(args_, msg::NODE_CENTRAL, log_);
  follower.answer_writer<msg::CentralCommandPubSubType>(comm::topic::kCentral);
  return follower.run([&](const msg::PlantTick& t) {
    control::CentralInput in;
    in.t_s = t.t();
    in.pose = {t.x(), t.y(), t.theta()};
    in.v_x = t.v_x();
    in.n_active_L = t.sides()[msg::SIDE_L].n_active();
    in.n_active_R = t.sides()[msg::SIDE_R].n_active();
    const control::CentralOutput o = core_.step(in);
    msg::CentralCommand c;
    c.tick(t.tick());
    c.v_x_ref(o.v_x_ref);
    c.w_ref(o.w_ref);
    c.phidot_ref()[msg::SIDE_L] = o.phidot_ref_L;
    c.phidot_ref()[msg::SIDE_R] = o.phidot_ref_R;
    c.relay_count_for()[msg::SIDE_L] = static_cast<uint16_t>(o.relay_for_L);
    c.relay_count_for()[msg::SIDE_R] = static_cast<uint16_t>(o.relay_for_R);
    c.segment(static_cast<uint16_t>(o.segment));
    c.rejected(follower.rejected());
    follower.answer(c);
  });
}

}  // namespace maptr::central
