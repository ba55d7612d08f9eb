#include "control/level1/agent_core.hpp"

#include <algorithm>
#include <cmath>

#include "model/motor.hpp"

namespace maptr::control {

AgentCore::AgentCore(AgentConfig c) : c_(c), pid_(c.pid) {}

void AgentCore::skip_to(const AgentInput& in) {
  // Tick k-1 as an idle agent with a fresh group and central steps it (below): not assigned,
  // PID reset, reference = central's, error followed. Only what tick k shows to hold: a gap the
  // tick filter made always ends so (at k-1 the group and central were fresh, so their commands
  // in force at k are at most two ticks old), while another gap (a lost tick, a pause) may end
  // inside an outage, where the agent goes on from its own state (a hold, a safe-stop ramp).
  if (in.group_stamp >= 0 && in.group_stamp >= in.tick - 2) {
    last_assigned_ = false;
    was_driving_ = false;
    pid_.reset();
  }
  if (in.central_stamp >= 0 && in.central_stamp >= in.tick - 2) {
    stop_ref_ = in.phidot_ref_prev_rad_s;
    prev_error_ = in.phidot_ref_prev_rad_s - in.phidot_prev_rad_s;
    has_prev_error_ = true;
  }
}

AgentOutput AgentCore::step(const AgentInput& in) {
  if (in.tick >= 1 && in.tick != last_tick_ + 1) skip_to(in);
  last_tick_ = in.tick;
  AgentOutput out;
  const double dt = c_.dt_s;
  // Assignment: fresh from the group, or held for a bounded time, then coast.
  bool assigned = false;
  const bool group_fresh = in.group_stamp >= 0 && in.tick - in.group_stamp <= 1;
  const double group_age_s = in.group_stamp < 0 ? 0.0 : (in.tick - in.group_stamp - 1) * dt;
  if (group_fresh) {
    assigned = in.assigned;
    last_assigned_ = assigned;
    out.state = assigned ? AgentState::kActive : AgentState::kIdle;
  } else if (in.group_stamp >= 0 && group_age_s <= c_.group_hold_s) {
    assigned = last_assigned_;
    out.state = assigned ? AgentState::kHolding : AgentState::kIdle;
  } else {
    out.state = in.group_stamp < 0 ? AgentState::kIdle : AgentState::kCoasting;
  }

  // Reference: from central, or a ramp to zero when central has been silent too long.
  double ref = in.phidot_ref_rad_s;
  const double central_age_s = in.central_stamp < 0 ? 0.0 : (in.tick - in.central_stamp - 1) * dt;
  if (in.central_stamp >= 0 && central_age_s > c_.central_timeout_s) {
    stop_ref_ = std::max(0.0, stop_ref_ - c_.stop_decel_mps2 / c_.wheel_radius_m * dt);
    ref = stop_ref_;
    if (assigned) out.state = AgentState::kStopping;
  } else {
    stop_ref_ = ref;
  }

  if (assigned) {
    // Bumpless start. Every active agent of a side sees the same speed error, so differences in
    // their integrators never decay: starting a newcomer at zero current (back-EMF) would leave
    // it carrying less than the others for good, and the side would draw more than an even split
    // (Joule losses grow with the square of the current). It starts at the side's level instead.
    if (!was_driving_) {
      if (in.side_active_V != 0.0 && has_prev_error_)
        pid_.align(in.side_active_V, prev_error_);
      else
        pid_.preload(c_.motor.back_emf_Vs * in.phidot_rad_s);
    }
    out.voltage_V = pid_.update(ref - in.phidot_rad_s, dt, c_.driver.floor_V(in.battery_V), in.battery_V);
    out.current_A = model::armature_current(c_.motor, c_.driver, out.voltage_V, in.phidot_rad_s);
    out.efficiency = model::efficiency(c_.motor, c_.driver, out.voltage_V, in.phidot_rad_s);
  } else {
    pid_.reset();
  }
  was_driving_ = assigned;
  prev_error_ = ref - in.phidot_rad_s;  // followed while idle too, for align()
  has_prev_error_ = true;
  return out;
}

}  // namespace maptr::control
