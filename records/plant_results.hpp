#pragma once
// plant.json, the plant's results of a run: the struct the plant fills and the launcher reads
// (it goes whole under `plant` in summary.json; records/summary_fields.cpp documents its keys).
// Writer and reader are the same field list (the NLOHMANN_DEFINE_TYPE_... lines below): a key
// is named once. A key missing from a file reads as its default; a key of the wrong type is
// a RecordError naming the file.
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "records/json_optional.hpp"

namespace maptr::records {

struct SideValues {
  double L = 0.0, R = 0.0;
};
struct SideCounts {
  int L = 0, R = 0;
};
struct SideSeries {  ///< one value per agent of each side
  std::vector<double> L, R;
};
struct PoseFigures {
  double x_m = 0.0, y_m = 0.0, theta_rad = 0.0;
};
/// How well the robot followed its path (the plant's tracking of central's reference).
struct PathFigures {
  double cross_track_max_m = 0.0, cross_track_max_t_s = 0.0, cross_track_rms_m = 0.0;
  double heading_error_max_rad = 0.0, final_position_error_m = 0.0;
};
/// A process joining or leaving the lock-step, as the plant saw it.
struct MembershipEvent {
  std::string name;   ///< process, e.g. "L3", "group-R"
  std::string event;  ///< "joined", "rejoined", "declared dead", ...
  double t_s = 0.0;
  double wall_ms = 0.0;
};
/// One fault of an agent's wheel the plant applied, and what the diagnosis made of it.
struct AgentFaultRecord {
  std::string target, mode;
  double value = 0.0, injected_s = 0.0;
  std::optional<double> detected_s, isolated_s;
  std::optional<std::string> diagnosed_mode;
  int relapses = 0;
  long long exposed_ticks = 0;
  std::optional<double> cleared_s, readmitted_s;
};
/// An agent isolated or readmitted by its group's diagnosis.
struct DiagnosisEvent {
  double t_s = 0.0;
  std::string target, event, diagnosed;
  bool false_detection = false;
};
struct AgentFaults {
  std::vector<AgentFaultRecord> faults;
  std::vector<DiagnosisEvent> diagnoses;
  int false_detections = 0;
};

/// Where the energy drawn from the batteries went (the integrated ledgers of the plant's state):
/// drawn_J = kinetic_end_J - kinetic_start_J + joule_loss_J + mech_loss_J + emf_loss_J, to the
/// integrator's tolerance.
struct EnergyLedger {
  double drawn_J = 0.0;          ///< from both batteries, net of regeneration
  double kinetic_start_J = 0.0;  ///< kinetic energy at t = 0 (translation, yaw, wheels)
  double kinetic_end_J = 0.0;    ///< kinetic energy at the end
  double joule_loss_J = 0.0;     ///< I^2 R in the windings + braking power the drivers dissipated
  double mech_loss_J = 0.0;      ///< ground friction + motor friction + viscous drag
  double emf_loss_J = 0.0;       ///< (K_e - K_T) I phidot: the datasheet's K_e != K_T
};

struct PlantResults {
  std::string status, end_reason;
  double sim_time_s = 0.0;
  long long ticks = 0;
  double tick_hz = 0.0, loop_wall_s = 0.0;
  double distance_m = 0.0, energy_J = 0.0;
  SideValues energy_side_J;
  EnergyLedger energy_ledger;
  double mean_active_agents = 0.0;
  SideCounts active_agents, live_agents;
  SideValues battery_discharge_mAh, battery_state_mAh, battery_V;
  SideSeries agent_active_s;  ///< each agent's time driving, s
  PoseFigures pose;
  double final_speed_mps = 0.0;
  PathFigures path;
  double max_speed_error_pct = 0.0, rms_speed_error_pct = 0.0;
  uint64_t rejected_samples = 0;
  std::map<std::string, uint64_t> rejected_by_process;  ///< by process (the plant's own and each follower's)
  std::map<std::string, uint64_t> rejected_by_kind;     ///< the plant's own, by kind
  uint64_t late_samples = 0, missed_deadlines = 0, tick_repairs = 0, declared_dead_by_deadline = 0;
  std::string loop_scheduling = "normal";
  std::map<std::string, uint64_t> answers_taken;  ///< answers the plant used, by topic
  nlohmann::json tick_timing_us = nlohmann::json::object();
  nlohmann::json group_wear = nlohmann::json::object();
  std::vector<MembershipEvent> membership_events;
  AgentFaults agent_faults;
};

// The keys of plant.json: each struct's members, by their names.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(SideValues, L, R)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(SideCounts, L, R)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(SideSeries, L, R)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(PoseFigures, x_m, y_m, theta_rad)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(PathFigures, cross_track_max_m, cross_track_max_t_s,
                                                cross_track_rms_m, heading_error_max_rad,
                                                final_position_error_m)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(EnergyLedger, drawn_J, kinetic_start_J, kinetic_end_J,
                                                joule_loss_J, mech_loss_J, emf_loss_J)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(MembershipEvent, name, event, t_s, wall_ms)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(AgentFaultRecord, target, mode, value, injected_s, detected_s,
                                                isolated_s, diagnosed_mode, relapses, exposed_ticks,
                                                cleared_s, readmitted_s)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(DiagnosisEvent, t_s, target, event, diagnosed,
                                                false_detection)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(AgentFaults, faults, diagnoses, false_detections)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(
    PlantResults, status, end_reason, sim_time_s, ticks, tick_hz, loop_wall_s, distance_m, energy_J,
    energy_side_J, energy_ledger, mean_active_agents, active_agents, live_agents, battery_discharge_mAh, battery_state_mAh,
    agent_active_s, battery_V, pose, final_speed_mps, path, max_speed_error_pct, rms_speed_error_pct,
    rejected_samples, rejected_by_process, rejected_by_kind, late_samples, missed_deadlines, tick_repairs,
    declared_dead_by_deadline, loop_scheduling, answers_taken, tick_timing_us, group_wear, membership_events,
    agent_faults)

nlohmann::json to_json(const PlantResults& r);
/// Throws RecordError naming `what` (a file) when a key holds the wrong type.
PlantResults plant_results_from_json(const nlohmann::json& j, const std::string& what);

void write_plant_results(const std::string& run_dir, const PlantResults& r);
/// The plant's results of the run in run_dir; nullopt when the plant left none. Throws RecordError
/// when the file is there but is not plant.json.
std::optional<PlantResults> read_plant_results(const std::string& run_dir);

}  // namespace maptr::records
