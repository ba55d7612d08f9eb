#include "deploy/report/run_plot.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/scenario.hpp"
#include "deploy/report/gnuplot.hpp"
#include "records/run_files.hpp"
#include "records/summary.hpp"

namespace maptr::deploy::report {

namespace {
constexpr const char* kStem = "run";
constexpr const char* kFrameSize = "1700,1250";
constexpr const char* kFaultColour = "#c0392b";
constexpr const char* kMemberColour = "#2471a3";
/// The agents panel reaches this many times the agents per side.
constexpr double kAgentHeadroom = 1.15;
/// Screen fractions: the time panels span [kTimeLeft, kTimeRight] from kTop down to kBottom,
/// each with its key just right of it at kKeyX; the path panel sits in the right column, the
/// notes under it.
constexpr double kTimeLeft = 0.055, kTimeRight = 0.46, kKeyX = 0.465, kTop = 0.945, kBottom = 0.045,
                 kGap = 0.012;
constexpr const char* kPathOrigin = "0.56,0.30";
constexpr const char* kPathSize = "0.44,0.66";
constexpr double kNoteX = 0.60, kNoteTop = 0.26, kNoteStep = 0.025;
/// The wear panel, under the notes in the right column.
constexpr const char* kWearOrigin = "0.56,0.02";
constexpr const char* kWearSize = "0.42,0.17";
/// The events panel: characters of its 9-point font across the time panels, and its rows.
constexpr double kEventChars = 120;
constexpr int kEventRows = 7;

std::string fmt(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

/// A vertical line at each event.
std::string event_lines(const std::vector<RunEvent>& events) {
  std::string s = "unset arrow\nunset label\n";
  for (const auto& e : events) {
    const char* colour = e.fault ? kFaultColour : kMemberColour;
    s += "set arrow from " + fmt(e.t_s) + ", graph 0 to " + fmt(e.t_s) + ", graph 1 nohead lc rgb '" +
         colour + "' dt " + (e.fault ? "1" : "2") + "\n";
  }
  return s;
}

/// The events panel: each event numbered and named at its time, in rows that do not overlap.
std::string events_panel(const std::vector<RunEvent>& events, double t0, double t1) {
  const std::vector<int> rows = label_rows(events, t0, t1, kEventChars, kEventRows);
  const int n_rows = rows.empty() ? 1 : *std::max_element(rows.begin(), rows.end()) + 1;
  std::string s = "set ylabel 'events'\nset yrange [0:" + fmt(n_rows) + "]\nunset ytics\nset grid noytics\n";
  for (std::size_t i = 0; i < events.size(); ++i) {
    const char* colour = events[i].fault ? kFaultColour : kMemberColour;
    s += "set label '" + std::to_string(i + 1) + " " + events[i].label + "' at " + fmt(events[i].t_s) + "," +
         fmt(n_rows - rows[i] - 0.5) + " left offset 0.2,0 font ',9' tc rgb '" + colour + "' front\n";
  }
  return s + "plot NaN notitle\nset ytics\nset grid ytics\nset autoscale y\n";
}

/// Each placed event as a point on the path, numbered beside it.
std::string event_points(const std::vector<RunEvent>& events) {
  std::string s = "unset arrow\nunset label\n";
  for (std::size_t i = 0; i < events.size(); ++i) {
    const auto& e = events[i];
    if (!e.placed) continue;
    const char* colour = e.fault ? kFaultColour : kMemberColour;
    // Numbered as in the events panel: names would cover one another where the robot stood.
    s += "set label '" + std::to_string(i + 1) + "' at " + fmt(e.x_m) + "," + fmt(e.y_m) +
         " point pt 7 ps 1.3 lc rgb '" + colour + "' offset 0.5," + fmt(0.8 - 0.8 * static_cast<double>(i % 3)) +
         " font ',9' tc rgb '" + colour + "' front\n";
  }
  return s;
}

/// Margins of time panel i of n (0 at the top) and its key, right of it.
std::string time_frame(int i, int n) {
  const double h = (kTop - kBottom) / n;
  const double top = kTop - i * h, bottom = top - h + kGap;
  return "set tmargin at screen " + fmt(top) + "\nset bmargin at screen " + fmt(bottom) +
         "\nset key at screen " + fmt(kKeyX) + "," + fmt(top) + " left top Left reverse samplen 2\n";
}

std::string speed_panel(const std::string& r) {
  const std::string ref = "((column(\"ref_L_radps\")+column(\"ref_R_radps\"))/2*" + r + ")";
  return "set ylabel 'speed, m/s'\n"
         "plot 'trace.csv' using \"t_s\":\"v_x_mps\" with lines lw 2 title 'v_x', \\\n"
         "     '' using \"t_s\":" +
         ref + " with lines lw 1 dt 2 lc rgb 'black' title 'reference'\n";
}

/// Yaw rate and the reference's: r (phidot_ref_R - phidot_ref_L) / a.
std::string yaw_panel(const std::string& r, const std::string& a) {
  const std::string ref = "((column(\"ref_R_radps\")-column(\"ref_L_radps\"))*" + r + "/" + a + ")";
  return "set ylabel 'yaw rate, rad/s'\n"
         "plot 'trace.csv' using \"t_s\":\"w_radps\" with lines lw 2 title 'w', \\\n"
         "     '' using \"t_s\":" +
         ref + " with lines lw 1 dt 2 lc rgb 'black' title 'reference'\n";
}

std::string heading_panel() {
  return "set ylabel 'heading, rad'\n"
         "plot 'trace.csv' using \"t_s\":\"theta_rad\" with lines lw 2 title 'theta', \\\n"
         "     '' using \"t_s\":\"ref_theta_rad\" with lines lw 1 dt 2 lc rgb 'black' title 'reference'\n";
}

std::string cross_track_panel() {
  return "set ylabel 'cross-track, m'\n"
         "plot 'trace.csv' using \"t_s\":\"cross_track_m\" with lines lw 2 lc rgb '#8e44ad' "
         "title 'cross-track (> 0: left)', 0 with lines lc rgb 'gray60' notitle\n";
}

std::string agents_panel(int per_side) {
  return "set ylabel 'agents'\nset yrange [0:" + fmt(per_side * kAgentHeadroom) + "]\n" +
         "plot 'trace.csv' using \"t_s\":\"n_active_L\" with steps lw 5 lc rgb '#c39bd3' title 'active L', \\\n"
         "     '' using \"t_s\":\"n_active_R\" with steps lw 1.5 lc rgb '#117a65' title 'active R', \\\n"
         "     '' using \"t_s\":\"n_live_L\" with steps lw 2 dt 2 lc rgb 'black' title 'live L', \\\n"
         "     '' using \"t_s\":\"n_live_R\" with steps lw 2 dt 3 lc rgb 'gray40' title 'live R'\n"
         "set autoscale y\n";
}

std::string energy_panel() {
  return "set ylabel 'energy, kJ'\n"
         "plot 'trace.csv' using \"t_s\":(column(\"energy_J\")/1000) with lines lw 2 title 'energy'\n";
}

std::string battery_panel() {
  return "set ylabel 'battery, V'\n"
         "plot 'trace.csv' using \"t_s\":\"battery_V_L\" with lines lw 5 lc rgb '#c39bd3' title 'battery L', \\\n"
         "     '' using \"t_s\":\"battery_V_R\" with lines lw 1.5 lc rgb '#117a65' title 'battery R'\n";
}

/// The robot's path against the reference's in the plane, equal scales, events on it.
std::string path_panel(const std::vector<RunEvent>& events) {
  return "set lmargin -1\nset rmargin -1\nset tmargin -1\nset bmargin -1\n"
         "set origin " +
         std::string(kPathOrigin) + "\nset size " + kPathSize +
         "\nset size ratio -1\nset format x '%g'\nset xlabel 'x, m'\nset ylabel 'y, m'\n"
         "set title 'path in the plane (equal scales)'\nset key below Right noreverse samplen 4\n"
         "set autoscale x\nset autoscale y\nset offsets graph 0.03, graph 0.03, graph 0.03, graph 0.03\n" +
         event_points(events) +
         "plot 'trace.csv' using \"ref_x_m\":\"ref_y_m\" with lines lw 7 lc rgb '#bbbbbb' title 'reference', "
         "\\\n"
         "     '' using \"x_m\":\"y_m\" with lines lw 1.5 lc rgb '#1f4e9f' title 'robot', \\\n"
         "     '' every ::0::0 using \"x_m\":\"y_m\" with points pt 9 ps 2 lc rgb 'black' title 'start'\n";
}

/// Each agent's wear at the end, a bar per agent, L then R.
std::string wear_panel(const std::vector<double>& L, const std::vector<double>& R) {
  // The script reads comma-separated data (gnuplot.cpp): so does this block (index, name, m, side).
  // At most about 16 names on the axis: every agent up to 16, every 2nd up to 32, ...
  const std::size_t step = std::max<std::size_t>(1, (L.size() + R.size() + 15) / 16);
  std::string s = "$wear << EOD\n";
  for (std::size_t i = 0; i < L.size() + R.size(); ++i) {
    const bool left = i < L.size();
    const std::size_t k = left ? i : i - L.size();
    s += std::to_string(i) + "," + (k % step == 0 ? (left ? "L" : "R") + std::to_string(k) : std::string()) + "," +
         fmt(left ? L[k] : R[k]) + "," + (left ? "0" : "1") + "\n";
  }
  return s + "EOD\nset lmargin -1\nset rmargin -1\nset tmargin -1\nset bmargin -1\nunset label\nunset arrow\n"
             "set origin " + kWearOrigin + "\nset size " + kWearSize +
             "\nset size noratio\nset title 'wear per agent at the end (m driven, the groups'' ledgers)' font ',10'\n"
             "set xlabel ''\nset ylabel 'm'\nset xrange [-0.7:" + fmt(static_cast<double>(L.size() + R.size()) - 0.3) +
             "]\nset yrange [0:*]\nset style fill solid 0.7\nset boxwidth 0.8\nunset key\nset xtics norotate font ',8'\n"
             "plot $wear using 1:3:($4 == 0 ? 0xc39bd3 : 0x117a65):xtic(2) with boxes lc rgb variable notitle\n";
}

/// Lines of text in the right column under the path (or in its place).
std::string notes(const std::vector<std::string>& lines) {
  std::string s;
  for (std::size_t i = 0; i < lines.size(); ++i)
    s += "set label '" + lines[i] + "' at screen " + fmt(kNoteX) + "," + fmt(kNoteTop - kNoteStep * i) +
         " font ',11'\n";
  return s;
}
}  // namespace

std::vector<int> label_rows(const std::vector<RunEvent>& events, double t0, double t1, double chars_across,
                            int max_rows) {
  const double per_char = t1 > t0 && chars_across > 0 ? (t1 - t0) / chars_across : 0.0;
  std::vector<double> row_end;  // where each row's last label ends, s
  std::vector<int> out;
  for (std::size_t i = 0; i < events.size(); ++i) {
    const double start = events[i].t_s;
    const double width = per_char * static_cast<double>(events[i].label.size() + std::to_string(i + 1).size() + 3);
    int row = -1;
    for (std::size_t r = 0; r < row_end.size() && row < 0; ++r)
      if (row_end[r] <= start) row = static_cast<int>(r);
    if (row < 0 && static_cast<int>(row_end.size()) < max_rows) {
      row = static_cast<int>(row_end.size());
      row_end.push_back(start);
    }
    if (row < 0)  // every row taken here: the one whose last label ends first
      row = static_cast<int>(std::min_element(row_end.begin(), row_end.end()) - row_end.begin());
    row_end[static_cast<std::size_t>(row)] = start + width;
    out.push_back(row);
  }
  return out;
}

std::vector<RunEvent> run_events(const nlohmann::json& summary) {
  std::vector<RunEvent> out;
  for (const auto& f : summary.value(records::summary_key::kFailures, nlohmann::json::array())) {
    if (!f.contains("at_s") || f.contains("skipped")) continue;
    const bool agent_fault = f.value("action", "") == "fault";
    // An agent's own fault is named by its mode ("short L3"), and its clear drawn too.
    out.push_back({f.value("at_s", 0.0), (agent_fault ? f.value("mode", "") : f.value("action", "")) + " " +
                                             f.value("target", ""), true});
    if (agent_fault && f.contains("cleared_s") && f["cleared_s"].is_number())
      out.push_back({f["cleared_s"].get<double>(), "clear " + f.value("target", ""), true});
  }
  const auto& plant = summary.value(records::summary_key::kPlant, nlohmann::json::object());
  for (const auto& m : plant.value("membership_events", nlohmann::json::array()))
    out.push_back({m.value("t_s", 0.0), m.value("name", "") + " " + m.value("event", ""), false});
  // What the groups made of the agents' faults: isolated (as what), let back.
  for (const auto& d : plant.value("agent_faults", nlohmann::json::object()).value("diagnoses", nlohmann::json::array()))
    out.push_back({d.value("t_s", 0.0),
                   d.value("target", "") + (d.value("event", "") == "isolated"
                                                ? " isolated (" + d.value("diagnosed", "") + ")"
                                                : std::string(" let back")),
                   false});
  std::stable_sort(out.begin(), out.end(),
                   [](const RunEvent& a, const RunEvent& b) { return a.t_s < b.t_s; });
  return out;
}

TracePath scan_trace(const std::string& text) {
  TracePath p;
  std::istringstream in(text);
  std::string line, cell;
  if (!std::getline(in, line)) return p;
  std::vector<std::string> head;
  for (std::istringstream h(line); std::getline(h, cell, ',');) head.push_back(cell);
  auto index = [&](const char* name) {
    const auto it = std::find(head.begin(), head.end(), name);
    return it == head.end() ? -1 : static_cast<int>(it - head.begin());
  };
  p.has_path = index("ref_x_m") >= 0 && index("ref_y_m") >= 0 && index("ref_theta_rad") >= 0 &&
               index("cross_track_m") >= 0;
  const int it = index("t_s"), ix = index("x_m"), iy = index("y_m");
  if (it < 0 || ix < 0 || iy < 0) return p;
  while (std::getline(in, line)) {
    std::vector<std::string> v;
    for (std::istringstream r(line); std::getline(r, cell, ',');) v.push_back(cell);
    if (static_cast<int>(v.size()) <= std::max({it, ix, iy})) continue;
    try {
      const double t = std::stod(v[it]), x = std::stod(v[ix]), y = std::stod(v[iy]);
      p.t_s.push_back(t);
      p.x_m.push_back(x);
      p.y_m.push_back(y);
    } catch (const std::exception&) {
    }
  }
  return p;
}

void place_events(std::vector<RunEvent>& events, const TracePath& p) {
  if (p.t_s.empty()) return;
  for (auto& e : events) {
    const auto after = std::upper_bound(p.t_s.begin(), p.t_s.end(), e.t_s);
    const std::size_t k = after == p.t_s.begin() ? 0 : static_cast<std::size_t>(after - p.t_s.begin()) - 1;
    e.placed = true;
    e.x_m = p.x_m[k];
    e.y_m = p.y_m[k];
  }
}

std::vector<std::string> path_notes(const nlohmann::json& summary, bool has_path) {
  if (!has_path)
    return {"No path panels: this trace.csv has no reference pose",
            "(ref_x_m, ref_y_m, ref_theta_rad, cross_track_m):",
            "it was written before the robot followed paths."};
  const auto p = summary.value("path", nlohmann::json::object());
  if (p.empty()) return {};
  auto f = [&](const char* k, int digits) {
    if (!p.contains(k) || !p[k].is_number()) return std::string("-");
    char b[32];
    std::snprintf(b, sizeof(b), "%.*f", digits, p[k].get<double>());
    return std::string(b);
  };
  return {"cross-track max " + f("cross_track_max_m", 3) + " m at " + f("cross_track_max_t_s", 1) +
              " s, rms " + f("cross_track_rms_m", 3) + " m",
          "heading error max " + f("heading_error_max_rad", 3) + " rad",
          "final position error " + f("final_position_error_m", 3) + " m"};
}

std::string run_plot_body(const RunPlotSpec& spec, const std::vector<RunEvent>& events) {
  const std::string r = fmt(spec.wheel_radius_m);
  const bool with_events = spec.t1 > spec.t0 && !events.empty();
  std::vector<std::string> panels;
  if (with_events) panels.push_back(events_panel(events, spec.t0, spec.t1));
  panels.push_back(speed_panel(r));
  if (spec.has_path) {
    panels.push_back(yaw_panel(r, fmt(spec.track_m)));
    panels.push_back(heading_panel());
    panels.push_back(cross_track_panel());
  }
  for (const auto& p : {agents_panel(spec.per_side), energy_panel(), battery_panel()}) panels.push_back(p);
  std::string b = "set multiplot title '" + spec.title + "' font ',13'\nset grid\n";
  b += "set lmargin at screen " + fmt(kTimeLeft) + "\nset rmargin at screen " + fmt(kTimeRight) +
       "\nset format x ''\n" +
       (spec.t1 > spec.t0 ? "set xrange [" + fmt(spec.t0) + ":" + fmt(spec.t1) + "]\n" : "set autoscale xfix\n");
  const int n = static_cast<int>(panels.size());
  for (int i = 0; i < n; ++i) {
    b += time_frame(i, n) + event_lines(events);
    if (i == n - 1) b += "set format x '%g'\nset xlabel 'simulated time, s'\n" + notes(spec.notes);
    b += panels[i];
  }
  if (spec.has_path) b += path_panel(events);
  if (!spec.wear_L.empty() || !spec.wear_R.empty()) b += wear_panel(spec.wear_L, spec.wear_R);
  return b + "unset multiplot\n";
}

bool draw_run_plot(const std::string& run_dir) {
  for (const char* f : {"trace.csv", "summary.json", "scenario.yaml"})
    if (!std::filesystem::exists(run_dir + "/" + f)) {
      std::fprintf(stderr, "maptr: no %s in %s: cannot draw run.png\n", f, run_dir.c_str());
      return false;
    }
  const config::Scenario sc = config::load_scenario(run_dir + "/scenario.yaml");
  const records::Summary s = records::Summary::read(records::summary_path(run_dir));
  std::ostringstream text;
  text << std::ifstream(records::trace_path(run_dir)).rdbuf();
  const TracePath path = scan_trace(text.str());
  std::vector<RunEvent> events = run_events(s.data());
  place_events(events, path);
  RunPlotSpec spec;
  spec.title = sc.name + ": " + std::to_string(sc.robot.agents) + " agents, " + sc.robot.driver.name() +
               " driver, mode " + sc.mode + ", status " + s.status();
  spec.wheel_radius_m = sc.robot.wheel_radius_m;
  spec.track_m = sc.robot.track_m;
  spec.per_side = sc.robot.per_side();
  spec.has_path = path.has_path;
  spec.notes = path_notes(s.data(), path.has_path);
  if (!path.t_s.empty()) {
    spec.t0 = path.t_s.front();
    spec.t1 = path.t_s.back();
  }
  const auto wear = s.data().value("plant", nlohmann::json::object()).value("group_wear", nlohmann::json::object());
  for (const auto& [side, out] : {std::pair<const char*, std::vector<double>*>{"L", &spec.wear_L}, {"R", &spec.wear_R}})
    for (const auto& w : wear.value(side, nlohmann::json::object()).value("wear_m", nlohmann::json::array()))
      if (w.is_number()) out->push_back(w.get<double>());
  return draw_plot(run_dir, kStem, "run.png of " + run_dir + " (maptr plot RUN redraws it)",
                   PlotFrame{kFrameSize, ",10"}, run_plot_body(spec, events));
}

}  // namespace maptr::deploy::report
