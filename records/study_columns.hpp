#pragma once
// The columns of every result table of the studies (`maptr experiment`, `maptr bench`,
// `maptr compare`): each table's CSV header and markdown headings, in file order. A result table
// is a file format (records/result_table.hpp writes and reads it), so its columns live here, one
// function per table, beside the columns several tables share.
#include <string>
#include <vector>

#include "records/result_table.hpp"

namespace maptr::records::columns {

/// Columns several tables share (same key, heading and decimals wherever they appear).
inline const ResultColumn kStatus{"status", "status", -1};
inline const ResultColumn kTraceSha256{"trace_sha256", "trace sha256", -1};
inline const ResultColumn kEnergyKJ{"energy_kJ", "energy kJ", 3};
inline const ResultColumn kMileage{"mileage", "mileage m/J", 4};
inline const ResultColumn kActiveMean{"active_mean", "active (mean, 2nd half)", 2};
inline const ResultColumn kActiveEnd{"active_end", "active (end, L+R)", 0};
inline const ResultColumn kDistance{"distance_m", "distance m", 2};
inline const ResultColumn kCrossTrackMax{"cross_track_max_m", "cross-track max m", 3};
inline const ResultColumn kFinalPositionError{"final_position_error_m", "final position error m", 3};
inline const ResultColumn kEffNO{"eff_NO", "eff NO", 3};
inline const ResultColumn kEffEC{"eff_EC", "eff EC", 3};
inline const ResultColumn kStatusNO{"status_NO", "status NO", -1};
inline const ResultColumn kStatusEC{"status_EC", "status EC", -1};
inline const ResultColumn kActiveECMean{"active_EC_mean", "active EC (mean, 2nd half)", 1};
inline const ResultColumn kSavingPct{"saving_pct", "saving %", 2};
inline const ResultColumn kDetected{"detected", "detected", 0};

/// Table POW (`maptr experiment table-pow`): NO against EC per gross mass, beside the paper.
std::vector<ResultColumn> table_pow();
/// An EC series over one condition (mass, speed, ...): `xkey` and `xhead` name the swept one.
std::vector<ResultColumn> ec_series(const std::string& xkey, const std::string& xhead);
/// The agent-count series: N and payload against energy and active agents.
std::vector<ResultColumn> agents();
/// Battery endurance: how long and how far each mode lasted.
std::vector<ResultColumn> battery();
/// Wear: idle time and ledger distance per agent (Level 3).
std::vector<ResultColumn> wear();
/// Kill tolerance: k agents killed per side, detection and recovery.
std::vector<ResultColumn> failures();
/// Agent faults: each fault mode, its detection, isolation and cost.
std::vector<ResultColumn> faults();
/// Turns: the loop per mode, path error and energy.
std::vector<ResultColumn> turn_loops();
/// A run's time series (the data of its plots).
std::vector<ResultColumn> run_series();
/// `maptr compare`: each variant against the first.
std::vector<ResultColumn> compare();
/// The IPC floor of `maptr bench floor`.
std::vector<ResultColumn> bench_floor();
/// `maptr bench scale`: one row per fleet.
std::vector<ResultColumn> bench_scale();
/// The per-process cost columns of `maptr bench scale` and `bench tick` (fleet_cost_json).
std::vector<ResultColumn> bench_fleet_cost();

}  // namespace maptr::records::columns
