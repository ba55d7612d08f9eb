#pragma once
// run.png: the picture of one run, drawn by gnuplot from the run folder's trace.csv and
// summary.json (run.gp is kept next to it). On the left, panels over simulated time: body speed
// and its reference (m/s), yaw rate and the reference's (rad/s), heading and the reference's
// (rad), cross-track error (m), active and live agents per side, energy drawn (kJ), battery
// voltage per side (V); the side drawn first thick and pale, the other thin on top, so that
// equal curves stay visible. On the right, the path in the plane: the robot's x-y against the
// reference's, at equal scales, and under it each agent's wear (m driven, from the groups'
// ledgers). Every fault (summary "failures", at its scheduled time) and every membership event
// the plant saw (summary "plant"."membership_events", at its simulated time) is a vertical line
// across the time panels, numbered and named in the events panel on top (labels in rows, none
// over another), and a numbered point on the path where the robot was at that time. A trace written before paths (no reference pose columns) gets the
// old four time panels and a note where the path would be.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace maptr::deploy::report {

/// A mark on the time axis of run.png (and on the path, at the robot's position then).
struct RunEvent {
  double t_s = 0;
  std::string label;    ///< e.g. "kill L3", "L3 died"
  bool fault = false;   ///< faults and membership events are drawn in two colours
  bool placed = false;  ///< x_m, y_m hold the robot's position at t_s
  double x_m = 0, y_m = 0;
};

/// The faults and membership events of a summary.json, in time order.
std::vector<RunEvent> run_events(const nlohmann::json& summary);

/// What run.png needs to know of trace.csv beyond its columns: whether it has the path columns
/// (ref_x_m, ref_y_m, ref_theta_rad, cross_track_m), and the robot's position over time.
struct TracePath {
  bool has_path = false;
  std::vector<double> t_s, x_m, y_m;
};

/// Reads the header and the t_s, x_m, y_m columns of trace.csv's text (rows that do not parse
/// are skipped).
TracePath scan_trace(const std::string& text);

/// Places each event at the robot's position at the last trace row not after its time (the
/// first row for an earlier event); nothing when the trace is empty.
void place_events(std::vector<RunEvent>& events, const TracePath& p);

/// The row (0 the top) of each event's label in the events panel: in time order, the first row
/// whose labels end left of this one's start, a label taking `label.size() + 3` characters of
/// the `chars_across` that span [t0, t1]; at most `max_rows` rows (beyond, the emptiest).
std::vector<int> label_rows(const std::vector<RunEvent>& events, double t0, double t1, double chars_across,
                            int max_rows);

/// The gnuplot body of run.png for a trace of wheel radius `wheel_radius_m`, track `track_m`,
/// `per_side` agents per side, these events, with or without the path panels.
struct RunPlotSpec {
  std::string title;
  double wheel_radius_m = 0.035, track_m = 0.2;
  int per_side = 8;
  bool has_path = true;
  std::vector<std::string> notes;  ///< lines of text under the path (e.g. its tracking figures)
  double t0 = 0, t1 = 0;           ///< the trace's time span (t1 <= t0: no events panel)
  std::vector<double> wear_L, wear_R;  ///< m per agent at the end ("": no wear panel)
};
std::string run_plot_body(const RunPlotSpec& spec, const std::vector<RunEvent>& events);

/// The lines under the path: summary.json's `path` figures, or why there is no path panel.
std::vector<std::string> path_notes(const nlohmann::json& summary, bool has_path);

/// Draws RUN_DIR/run.png (and run.gp) from RUN_DIR/trace.csv, summary.json and
/// scenario.yaml; false, with a message on stderr, when a file is missing or gnuplot fails.
bool draw_run_plot(const std::string& run_dir);

}  // namespace maptr::deploy::report
