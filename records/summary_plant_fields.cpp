// summary.json's keys from the plant's results (RUN_DIR/plant.json), documented: the second
// half of records/summary_fields.cpp's table (one key a line, as there).
#include "records/summary_fields.hpp"

namespace maptr::records::detail {

// clang-format off
/// The plant's results (RUN_DIR/plant.json); {} when the plant left none.
std::vector<SummaryField> plant_keys_run() {
  return {
      {"plant.status", "text", "", "The plant's view of the run: ok, degraded: <why> or aborted: stop signal"},
      {"plant.end_reason", "text", "", "duration reached, or why the run ended early (the speed stayed too far below its reference too long)"},
      {"plant.sim_time_s", "number", "s", "Simulated time at the end: ticks / tick_hz"},
      {"plant.ticks", "integer", "1", "Ticks integrated"},
      {"plant.tick_hz", "number", "Hz", "Ticks per simulated second (the scenario's tick_hz)"},
      {"plant.loop_wall_s", "number", "s", "Wall time of the plant's lock-step loop up to its report, without the time held at fault gates"},
      {"plant.distance_m", "number", "m", "Distance the robot travelled (integral of |v_x|)"},
      {"plant.energy_J", "number", "J", "Energy drawn from both batteries"},
      {"plant.energy_side_J.<side>", "number", "J", "Energy drawn from side L's or R's battery"},
      {"plant.energy_ledger.drawn_J", "number", "J", "Energy drawn from both batteries, net of regeneration (= plant.energy_J)"},
      {"plant.energy_ledger.kinetic_start_J", "number", "J", "Kinetic energy of the robot at t = 0 (translation, yaw, wheels)"},
      {"plant.energy_ledger.kinetic_end_J", "number", "J", "Kinetic energy of the robot at the end"},
      {"plant.energy_ledger.joule_loss_J", "number", "J", "I^2 R in the windings + braking power the drivers dissipated"},
      {"plant.energy_ledger.mech_loss_J", "number", "J", "Ground friction + motor friction + viscous drag"},
      {"plant.energy_ledger.emf_loss_J", "number", "J", "(K_e - K_T) I phidot, the datasheet's K_e != K_T; drawn_J = kinetic_end_J - kinetic_start_J + the three losses (property energy_balance)"},
      {"plant.mean_active_agents", "number", "1", "Mean number of agents driving per tick over the run, both sides together"},
      {"plant.active_agents.<side>", "integer", "1", "Agents of the side driving in the last tick"},
      {"plant.live_agents.<side>", "integer", "1", "Agents of the side the plant counted live (neither dead nor paused) at the end"},
      {"plant.battery_discharge_mAh.<side>", "number", "mAh", "Charge drawn from the side's battery during the run, without the initial discharge"},
      {"plant.battery_state_mAh.<side>", "number", "mAh", "Charge drawn from the side's battery at the end, the scenario's initial discharge included"},
      {"plant.battery_V.<side>", "number", "V", "The side's battery voltage at the end (battery model, from the charge drawn)"},
      {"plant.agent_active_s.<side>[]", "number", "s", "Time each agent of the side drove, in agent order (L0, L1, ...)"},
      {"plant.pose.x_m", "number", "m", "Final position, world x"},
      {"plant.pose.y_m", "number", "m", "Final position, world y"},
      {"plant.pose.theta_rad", "number", "rad", "Final heading"},
      {"plant.final_speed_mps", "number", "m/s", "Body forward speed v_x at the end"},
      {"plant.path.cross_track_max_m", "number", "m", "Largest |cross-track error| after the first second (also top-level path)"},
      {"plant.path.cross_track_max_t_s", "number", "s", "Simulated time of the largest cross-track error"},
      {"plant.path.cross_track_rms_m", "number", "m", "RMS cross-track error after the first second"},
      {"plant.path.heading_error_max_rad", "number", "rad", "Largest |heading error| after the first second, while the reference moves"},
      {"plant.path.final_position_error_m", "number", "m", "Distance from the robot's last pose to the reference's last pose"},
      {"plant.max_speed_error_pct", "number", "%", "Largest |v_x - v_ref| / v_ref over the ticks after the speed first reached its reference"},
      {"plant.rms_speed_error_pct", "number", "%", "RMS speed error over the ticks after the speed first reached its reference"},
      {"plant.rejected_samples", "integer", "1",
       "Samples the plant dropped (forged, malformed, other_tick, conflicting, stale, stale_copy, undecodable); late answers are apart"},
      {"plant.rejected_by_process.<process>", "integer", "1",
       "Drops by process: the plant's own (key plant) and what each agent, group and central last reported in its answers"},
      {"plant.rejected_by_kind.<kind>", "integer", "1",
       "The plant's drops by kind (forged, malformed, other_tick, conflicting, stale, stale_copy, undecodable) and its late answers (late)"},
      {"plant.late_samples", "integer", "1",
       "Answers from their rightful sender that came after the plant had gone past the next tick: not used, not rejected"},
      {"plant.missed_deadlines", "integer", "1", "With realtime: ticks done after their wall-clock due time (0 without realtime)"},
      {"plant.loop_scheduling", "text", "",
       "What the lock-step thread ran under: normal, SCHED_FIFO <priority> on CPU <n>, or normal (SCHED_FIFO ... refused: <why>)"}
  };
}

/// The plant's results, continued.
std::vector<SummaryField> plant_keys_faults() {
  return {
      {"plant.tick_repairs", "integer", "1", "Ticks sent again because answers were missing (samples taken for lost)"},
      {"plant.answers_taken.<topic>", "integer", "1",
       "Answers the plant used, by topic (maptr/agent_reply, maptr/group, maptr/central): at most one per member and tick"},
      {"plant.tick_timing_us.<part>.median", "number", "µs",
       "Median wall time of a tick's part: publish, first_reply, barrier, integrate, tick (published to integrated) "
       "or period (one publish to the next: what a tick costs the run's wall time)"},
      {"plant.tick_timing_us.<part>.mean", "number", "µs", "Mean wall time of the part (period: 1 / (real-time factor x tick rate))"},
      {"plant.tick_timing_us.<part>.p90", "number", "µs", "90th percentile of the part's wall time (nearest rank below)"},
      {"plant.tick_timing_us.<part>.p99", "number", "µs", "99th percentile of the part's wall time (nearest rank below)"},
      {"plant.tick_timing_us.<part>.max", "number", "µs", "Longest wall time of the part"},
      {"plant.tick_timing_us.<part>.n", "integer", "1", "Ticks measured for the part (first_reply: ticks with a reply; a part with none is {})"},
      {"plant.tick_timing_us.slowest_1pct.threshold_us", "number", "µs", "The shortest of the slowest 1 % of the ticks (by tick)"},
      {"plant.tick_timing_us.slowest_1pct.n", "number", "1", "Ticks in the slowest 1 % (at least one)"},
      {"plant.tick_timing_us.slowest_1pct.<set>.<share>", "number", "%",
       "Of the slowest 1 % (set slowest) and of all ticks (set all): answered last by an agent, a group or central "
       "(last_agent_pct, last_group_pct, last_central_pct; last_none_pct: no answer), with a trace row written "
       "(traced_pct), with a group's Level-2 solve under way when it answered (level2_solving_pct)"},
      {"plant.tick_timing_us.slowest_1pct.ticks[].tick", "integer", "1", "One of the five slowest ticks (slowest first): k"},
      {"plant.tick_timing_us.slowest_1pct.ticks[].us", "number", "µs", "Its wall time, published to integrated"},
      {"plant.tick_timing_us.slowest_1pct.ticks[].longest_part", "text", "", "Its longest part: publish, barrier or integrate"},
      {"plant.tick_timing_us.slowest_1pct.ticks[].longest_part_us", "number", "µs", "That part's wall time"},
      {"plant.declared_dead_by_deadline", "integer", "1", "Agents declared dead for missing a tick's deadline (groups and central not counted)"},
      {"plant.membership_events[].name", "text", "", "The process: an agent, group-L, group-R or central"},
      {"plant.membership_events[].event", "text", "",
       "died (launcher), lost (DDS liveliness), missed the tick deadline, paused (launcher), resumed (launcher), started (launcher), rejoined"},
      {"plant.membership_events[].t_s", "number", "s", "Simulated time at which the plant applied it"},
      {"plant.membership_events[].wall_ms", "number", "ms", "The plant's wall clock when it applied it, ms since the epoch"},
      {"plant.group_wear.<side>.wear_m[]", "number", "m",
       "The side's wear ledger in the group's last status: distance each agent drove while active, in agent order"},
      {"plant.group_wear.<side>.regressions", "integer", "1", "Group statuses in which an agent's ledger distance went down (a regression)"},
      {"plant.group_wear.<side>.largest_drop_m", "number", "m", "Largest drop of an agent's ledger distance; 0 without a regression"},
      {"plant.group_wear.<side>.first_regression_s", "number|null", "s", "Simulated time of the first regression; null without one"},
      {"plant.agent_faults.faults[].target", "text", "", "The agent the fault broke"},
      {"plant.agent_faults.faults[].mode", "text", "", "open, short, torque, resistance, stuck (in the motor) or sensor, erratic, liar (in the agent)"},
      {"plant.agent_faults.faults[].value", "number", "1",
       "The fault's size (torque or resistance factor, stuck V, sensor rad/s, erratic V; 0 for open, short, liar)"},
      {"plant.agent_faults.faults[].injected_s", "number", "s", "When the plant applied it (the first tick at or after its scheduled time)"},
      {"plant.agent_faults.faults[].detected_s", "number|null", "s", "Time of the group status that first flagged the agent; null: never"},
      {"plant.agent_faults.faults[].isolated_s", "number|null", "s", "From when the agent was no longer assigned nor counted (a tick after detection)"},
      {"plant.agent_faults.faults[].diagnosed_mode", "text|null", "", "What the group took the fault for; null when never detected"},
      {"plant.agent_faults.faults[].relapses", "integer", "1", "Times the agent was flagged again after a probation"},
      {"plant.agent_faults.faults[].exposed_ticks", "integer", "1",
       "Ticks in which the fault acted on the drive (the agent drove, or its motor carried current, while connected)"},
      {"plant.agent_faults.faults[].cleared_s", "number|null", "s", "When a clear or the agent's next fault ended it; null: in force to the end"},
      {"plant.agent_faults.faults[].readmitted_s", "number|null", "s", "When the group let the agent back after its last probation; null: never"},
      {"plant.agent_faults.diagnoses[].t_s", "number", "s", "Simulated time of the group status that raised or lowered the flag"},
      {"plant.agent_faults.diagnoses[].target", "text", "", "The agent flagged or let back"},
      {"plant.agent_faults.diagnoses[].event", "text", "", "isolated (flag raised) or readmitted (flag lowered)"},
      {"plant.agent_faults.diagnoses[].diagnosed", "text", "", "What the group took it for; empty for readmitted"},
      {"plant.agent_faults.diagnoses[].false_detection", "bool", "", "True when the agent was flagged with no fault in force on it"},
      {"plant.agent_faults.false_detections", "integer", "1", "Flags raised on an agent with no fault in force (healthy agents isolated)"}
  };
}
// clang-format on

}  // namespace maptr::records::detail
