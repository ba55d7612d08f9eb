#pragma once
// trace.csv: the plant's record of the run, one row every `trace_every` ticks. Row k holds the
// state at t_k and what was applied over [t_k, t_k+1]: pose, body speeds, wheel speeds and their
// references, the mean applied voltage, the summed current and the mean efficiency of the
// active agents per side, battery voltage and discharge, agent counts, energy and distance, the
// reference pose on the path and the cross-track error.
#include <cstdio>
#include <string>
#include <vector>

#include "records/csv.hpp"

namespace maptr::records {

/// One row of trace.csv (counts are whole numbers held as double).
struct TraceRow {
  double tick = 0, t_s = 0, x_m = 0, y_m = 0, theta_rad = 0, v_x_mps = 0, w_radps = 0;
  double phidot_L_radps = 0, phidot_R_radps = 0, ref_L_radps = 0, ref_R_radps = 0;
  double V_L_mean_V = 0, V_R_mean_V = 0, I_L_A = 0, I_R_A = 0, eff_L = 0, eff_R = 0;
  double battery_V_L = 0, battery_V_R = 0, discharge_L_mAh = 0, discharge_R_mAh = 0;
  double n_active_L = 0, n_active_R = 0, n_live_L = 0, n_live_R = 0;
  double energy_J = 0, distance_m = 0;
  double ref_x_m = 0, ref_y_m = 0, ref_theta_rad = 0;  ///< the path's reference pose at t_k
  double cross_track_m = 0;  ///< signed distance to the path (> 0: left of it)

  /// Mean of the two sides' wheel-speed references times the wheel radius, m/s.
  double ref_speed_mps(double wheel_radius_m) const;
};

/// A column of trace.csv and where its value lives in a TraceRow.
struct TraceColumn {
  ColumnSpec spec;
  double TraceRow::*value;
};

/// The columns of trace.csv, in file order.
const std::vector<TraceColumn>& trace_columns();

/// The header line of trace.csv (with its newline).
std::string trace_header();

/// One row of trace.csv as text (with its newline).
std::string format_trace_row(const TraceRow& r);

/// Writes trace.csv: the header at construction, then one flushed line per row. Throws
/// RecordError when `path` cannot be written.
struct TraceWriter : RowWriter<TraceRow, format_trace_row> {
  explicit TraceWriter(const std::string& path);
};

/// Reads trace.csv by column name. Throws RecordError naming a missing column or a malformed
/// number (file, line, column).
std::vector<TraceRow> read_trace(const std::string& path);

/// The same from text (the file's content).
std::vector<TraceRow> parse_trace(const std::string& text);

}  // namespace maptr::records
