#include "records/study_columns.hpp"

namespace maptr::records::columns {

std::vector<ResultColumn> table_pow() {
  return {{"gross_kg", "gross kg", 1},
          {"E_NO_kJ", "E_NO kJ", 2},
          {"E_NO_paper_kJ", "E_NO paper", 2},
          {"E_EC_kJ", "E_EC kJ", 2},
          {"E_EC_paper_kJ", "E_EC paper", 2},
          kSavingPct,
          {"saving_paper_pct", "saving paper", 2},
          {"active_EC_end", "active EC (end, L+R)", 0},
          kActiveECMean,
          {"active_paper", "active paper", 0},
          {"mileage_NO", "mileage NO m/J", 4},
          {"mileage_NO_paper", "NO paper", 4},
          {"mileage_EC", "mileage EC m/J", 4},
          {"mileage_EC_paper", "EC paper", 4},
          kEffNO,
          kEffEC,
          {"V_over_VB_EC", "V/V_B EC", 3},
          {"v_end_NO_mps", "v end NO m/s", 2},
          {"v_end_EC_mps", "v end EC m/s", 2},
          {"distance_NO_m", "distance NO m", 0, false},
          {"distance_EC_m", "distance EC m", 0, false},
          kStatusNO,
          kStatusEC};
}

std::vector<ResultColumn> ec_series(const std::string& xkey, const std::string& xhead) {
  return {{xkey, xhead, 1},
          {"energy_kJ", "energy kJ", 2},
          kMileage,
          {"eff_cruise", "eff (mean, 2nd half)", 3},
          kActiveMean,
          kActiveEnd,
          {"V_applied_V", "applied V (2nd half)", 2},
          {"V_over_VB", "V/V_B", 3},
          {"v_end_mps", "v end m/s", 2},
          {"l2_decisions", "Level-2 decisions", 0},
          {"l2_solve_ms", "Ipopt solve ms (median)", 1},
          {"oracle_differs", "Ipopt != oracle", 0},
          {"oracle_checked", "oracle checks", 0},
          kStatus};
}

std::vector<ResultColumn> agents() {
  return {{"series", "payload", -1},
          {"agents", "N", 0},
          {"gross_kg", "gross kg", 1},
          {"E_NO_kJ", "E_NO kJ", 3},
          {"E_EC_kJ", "E_EC kJ", 3},
          kSavingPct,
          {"active_EC_end", "active EC (end)", 0},
          kActiveECMean,
          kEffNO,
          kEffEC,
          kStatusNO,
          kStatusEC};
}

std::vector<ResultColumn> battery() {
  return {{"mode", "mode", -1},
          {"lasted_s", "lasted s", 0},
          {"distance_km", "distance km", 2},
          {"energy_kJ", "energy kJ", 1},
          kMileage,
          {"drawn_mAh", "drawn mAh (L)", 0},
          {"battery_V_end", "V_B at end", 2},
          {"eff_mean", "eff (mean, 2nd half)", 3},
          kActiveMean,
          {"end_reason", "end", -1},
          kStatus};
}

std::vector<ResultColumn> wear() {
  return {{"agents", "N", 0},
          kActiveMean,
          kActiveEnd,
          {"idle_mean_steps", "idle per agent (T_ON steps)", 2},
          {"idle_min_steps", "idle min", 2},
          {"idle_max_steps", "idle max", 2},
          {"idle_mean_s", "idle per agent s", 1},
          {"wear_min_m", "wear min m", 1},
          {"wear_max_m", "wear max m", 1},
          {"wear_spread_L_m", "spread L m", 1},
          {"wear_spread_R_m", "spread R m", 1},
          {"spread_bound_m", "bound m", 1},
          {"drove_in_cruise_L", "agents that drove in cruise L", 0},
          {"drove_in_cruise_R", "R", 0},
          kStatus};
}

std::vector<ResultColumn> failures() {
  return {{"killed_per_side", "killed per side", 0},
          {"tolerance", "tolerance N_i - N_a,i", 0},
          {"killed", "killed", -1},
          kDetected,
          {"detect_wall_ms_max", "detection wall ms (max)", 1},
          {"recovered", "recovered", 0},
          {"recovered_s_max", "recovered at s (latest)", 2},
          {"max_speed_error_pct", "max speed error % after kill", 2},
          {"final_speed_mps", "final speed m/s", 3},
          {"active_end_L", "active L (end)", 0},
          {"active_end_R", "active R (end)", 0},
          kEnergyKJ,
          {"eff_cruise", "eff (2nd half)", 3},
          kStatus};
}

std::vector<ResultColumn> faults() {
  return {{"mass_kg", "gross kg", 1},
          {"agents", "faulty agents (side L)", 0},
          {"mode", "mode", -1},
          {"mode_index", "mode index", 0, false, true},
          {"detection", "detection", -1},
          kDetected,
          {"detect_s_max", "detection s (latest)", 2},
          {"isolate_s_max", "isolation s (latest)", 2},
          {"diagnosed", "diagnosed as", -1},
          {"max_speed_error_pct", "max speed error % after the fault", 2},
          {"cross_track_max_m", "path error max m", 3},
          kEnergyKJ,
          {"energy_penalty_J", "energy penalty J (vs fault-free, before the stop)", 0},
          {"energy_penalty_run_J", "energy penalty J (whole run)", 0},
          kStatus};
}

std::vector<ResultColumn> turn_loops() {
  return {{"mode", "mode", -1},
          kEnergyKJ,
          kMileage,
          kDistance,
          {"active_mean", "active (mean, L+R)", 2},
          kCrossTrackMax,
          {"cross_track_rms_m", "cross-track rms m", 3},
          {"heading_error_max_rad", "heading error max rad", 3},
          kFinalPositionError,
          kStatus,
          kTraceSha256};
}

std::vector<ResultColumn> run_series() {
  return {{"t_s", "t (s)", 3},         {"v_x_mps", "v (m/s)", 5},
          {"ref_mps", "ref (m/s)", 5}, {"eff_agent", "eff", 5},
          {"n_active", "active", 3},   {"battery_V", "battery (V)", 4},
          {"V_applied_V", "V (V)", 4}, {"discharge_mAh", "mAh", 3},
          {"energy_kJ", "E (kJ)", 4},  {"distance_m", "distance (m)", 2}};
}

std::vector<ResultColumn> compare() {
  return {{"variant", "variant", -1},
          kStatus,
          {"energy_J", "energy J", 1},
          {"saving_pct", "saving vs first %", 2},
          {"mileage_m_per_J", "mileage m/J", 4},
          kDistance,
          kCrossTrackMax,
          kFinalPositionError,
          {"mean_active_agents", "mean active agents", 2},
          {"discharge_mAh", "battery discharge mAh (L+R)", 1},
          kTraceSha256};
}

std::vector<ResultColumn> bench_floor() {
  return {{"agents", "N", 0},
          {"workers", "workers W", 0},
          {"touch_kb", "KiB touched / worker / round", 0},
          {"median_us", "round median µs", 0},
          {"p99_us", "round p99 µs", 0},
          {"cpu_us_per_round", "CPU µs / round", 0},
          {"cpu_us_per_worker_round", "CPU µs / worker / round", 1},
          {"cs_per_round", "cs / round", 1}};
}

namespace {

/// What the slowest 1 % of a fleet's ticks had in common, beside all its ticks.
std::vector<ResultColumn> bench_slowest_ticks() {
  std::vector<ResultColumn> cols;
  const std::pair<const char*, const char*> shares[] = {{"last_agent_pct", "last answer an agent's %"},
                                                        {"last_group_pct", "last answer a group's %"},
                                                        {"last_central_pct", "last answer central's %"},
                                                        {"level2_solving_pct", "Level-2 solve under way %"},
                                                        {"traced_pct", "trace row written %"}};
  for (const auto& [key, what] : shares) {
    cols.push_back({std::string("slow_") + key, std::string("slowest 1 %: ") + what, 1});
    cols.push_back({std::string("all_") + key, std::string("all ticks: ") + what, 1});
  }
  return cols;
}

}  // namespace

std::vector<ResultColumn> bench_scale() {
  std::vector<ResultColumn> cols = {{"agents", "N", 0},
                                    {"mode", "mode", -1},
                                    {"hosts", "hosts", 0},
                                    {"started_by", "started by", -1},
                                    {"status", "status", -1, false, true},
                                    {"status_text", "status", -1, true, false},
                                    {"discovery_s", "discovery s", 2},
                                    {"ticks_per_wall_s", "ticks / wall s", 1},
                                    {"real_time_factor", "RTF (100 Hz)", 2},
                                    {"cpu_s_per_sim_s", "CPU s / sim s", 2},
                                    {"pss_agent_median_kB", "", 0, false, true},
                                    {"pss_agent_median_MB", "PSS agent median MB", 1, true, false},
                                    {"pss_agent_max_kB", "", 0, false, true},
                                    {"pss_agent_max_MB", "PSS agent max MB", 1, true, false},
                                    {"pss_total_kB", "", 0, false, true},
                                    {"pss_total_MB", "PSS total MB", 0, true, false},
                                    {"samples_per_tick", "DDS samples / tick", 0},
                                    {"bridge_bytes_per_tick", "bridge bytes / tick", 0},
                                    {"tick_median_us", "", 0, false, true},
                                    {"tick_median_ms", "tick median ms", 2, true, false},
                                    {"tick_p99_us", "", 0, false, true},
                                    {"tick_p99_ms", "tick p99 ms", 2, true, false},
                                    {"tick_mean_us", "tick mean µs", 0},
                                    {"tick_p90_us", "tick p90 µs", 0},
                                    {"tick_max_us", "tick max µs", 0},
                                    {"period_median_us", "period median µs", 0},
                                    {"period_mean_us", "period mean µs", 0},
                                    {"mean_over_median", "period mean / median", 2},
                                    {"floor_median_us", "floor median µs", 0},
                                    {"x_floor", "tick / floor", 1},
                                    {"dds_floor_median_us", "DDS floor median µs", 0},
                                    {"dds_floor_mean_us", "DDS floor mean µs", 0},
                                    {"x_dds_floor", "tick / DDS floor", 2},
                                    {"dds_floor_cpu_us_per_round", "DDS floor CPU µs / round", 0},
                                    {"dds_floor_resent", "DDS floor ticks resent", 0},
                                    {"dds_floor_first_round_us", "DDS floor first round µs", 0},
                                    {"first_tick_us", "fleet's tick 0 µs (0: not among the 5 slowest)", 0},
                                    {"dds_floor_problem", "DDS floor not measured: why", -1},
                                    {"floor_cs_per_round", "floor cs / round", 1},
                                    {"floor_cpu_us_per_round", "floor CPU µs / round", 0}};
  for (const auto& c : bench_fleet_cost()) cols.push_back(c);
  for (const auto& c : bench_slowest_ticks()) cols.push_back(c);
  // last: earlier columns keep their places
  cols.push_back({"record", "run.mcap records", -1});
  cols.push_back({"realtime", "paced to the wall clock", -1});
  cols.push_back({"tick_filter", "tick filter", -1});
  cols.push_back({"plant_scheduling", "plant lock-step thread", -1});
  cols.push_back({"steal_pct_fleet", "CPU steal % fleet", 1});
  cols.push_back({"steal_pct_floor", "CPU steal % floor", 1});
  return cols;
}

std::vector<ResultColumn> bench_fleet_cost() {
  return {{"cost_ticks", "cost window ticks", 0},
          {"cs_tick_plant", "cs / tick plant", 1},
          {"cs_tick_agent", "cs / tick agent (mean)", 2},
          {"cs_tick_agents", "cs / tick agents (all)", 1},
          {"cs_tick_group", "cs / tick group (mean)", 1},
          {"cs_tick_central", "cs / tick central", 1},
          {"cs_tick_ds", "cs / tick discovery server", 2},
          {"cpu_us_tick_plant", "CPU µs / tick plant", 0},
          {"cpu_us_tick_agent", "CPU µs / tick agent (mean)", 0},
          {"cpu_us_tick_agents", "CPU µs / tick agents (all)", 0},
          {"cpu_us_tick_group", "CPU µs / tick group (mean)", 0},
          {"cpu_us_tick_central", "CPU µs / tick central", 0},
          {"cpu_us_tick_ds", "CPU µs / tick discovery server", 1},
          {"cs_tick_launcher", "cs / tick launcher", 1},
          {"cpu_us_tick_groups", "CPU µs / tick groups (all)", 0},
          {"cpu_us_tick_launcher", "CPU µs / tick launcher (with recorder)", 0},
          {"cpu_us_tick_tick_path", "CPU µs / tick: lock-step main threads", 0},
          {"cpu_us_tick_level2", "CPU µs / tick: Level-2 threads", 0},
          {"cpu_us_tick_recorder", "CPU µs / tick: recorder thread", 0},
          {"cpu_us_tick_other_threads", "CPU µs / tick: other threads (Fast DDS, logs, launcher, server)", 0},
          {"cpu_us_tick_processes", "CPU µs / tick: all processes", 0},
          {"cpu_us_tick_watch", "CPU µs / tick: the bench's watch", 0},
          {"cpu_us_tick_machine", "CPU µs / tick: the machine (/proc/stat)", 0},
          {"cpu_accounted_pct", "accounted % of the machine", 1}};
}

}  // namespace maptr::records::columns
