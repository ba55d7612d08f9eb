#pragma once
// run.png: the picture of one run, drawn by gnuplot from the run folder's trace.csv and
// summary.json (run.gp is kept next to it). Four panels over simulated time: body speed
// and its reference (m/s), active and live agents per side, energy drawn (kJ), battery voltage
// per side (V). Every fault (summary "failures", at its scheduled time) and every membership
// event the plant saw (summary "plant"."membership_events", at its simulated time) is a
// vertical line across all panels, named on the top one.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace maptr::deploy::report {

/// A mark on the time axis of run.png.
struct RunEvent {
  double t_s = 0;
  std::string label;   ///< e.g. "kill L3", "L3 died"
  bool fault = false;  ///< faults and membership events are drawn in two colours
};

/// The faults and membership events of a summary.json, in time order.
std::vector<RunEvent> run_events(const nlohmann::json& summary);

/// The gnuplot body of run.png for a trace of wheel radius `wheel_radius_m`, `per_side` agents
/// per side and these events.
std::string run_plot_body(const std::string& title, double wheel_radius_m, int per_side,
                          const std::vector<RunEvent>& events);

/// Draws RUN_DIR/run.png (and run.gp) from RUN_DIR/trace.csv, summary.json and
/// scenario.yaml; false, with a message on stderr, when a file is missing or gnuplot fails.
bool draw_run_plot(const std::string& run_dir);

}  // namespace maptr::deploy::report
