#include "deploy/report/run_plot.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/scenario.hpp"
#include "deploy/report/gnuplot.hpp"
#include "records/summary.hpp"

namespace maptr::deploy::report {

namespace {
constexpr const char* kStem = "run";
constexpr const char* kFrameSize = "1200,1000";
constexpr const char* kFaultColour = "#c0392b";
constexpr const char* kMemberColour = "#2471a3";
/// The agents panel reaches this many times the agents per side.
constexpr double kAgentHeadroom = 1.15;

std::string fmt(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

/// A vertical line at each event; on the first panel also its name, rotated.
std::string event_lines(const std::vector<RunEvent>& events, bool labels) {
  std::string s = "unset arrow\nunset label\n";
  for (std::size_t i = 0; i < events.size(); ++i) {
    const auto& e = events[i];
    const char* colour = e.fault ? kFaultColour : kMemberColour;
    s += "set arrow from " + fmt(e.t_s) + ", graph 0 to " + fmt(e.t_s) + ", graph 1 nohead lc rgb '" +
         colour + "' dt " + (e.fault ? "1" : "2") + "\n";
    if (labels)
      s += "set label '" + e.label + "' at " + fmt(e.t_s) + ", graph " + fmt(0.97 - 0.12 * (i % 4)) +
           " rotate by 0 offset 0.3,0 font ',9' tc rgb '" + colour + "'\n";
  }
  return s;
}
}  // namespace

std::vector<RunEvent> run_events(const nlohmann::json& summary) {
  std::vector<RunEvent> out;
  for (const auto& f : summary.value(records::summary_key::kFailures, nlohmann::json::array()))
    if (f.contains("at_s") && !f.contains("skipped"))
      out.push_back({f.value("at_s", 0.0), f.value("action", "") + " " + f.value("target", ""), true});
  const auto& plant = summary.value(records::summary_key::kPlant, nlohmann::json::object());
  for (const auto& m : plant.value("membership_events", nlohmann::json::array()))
    out.push_back({m.value("t_s", 0.0), m.value("name", "") + " " + m.value("event", ""), false});
  std::stable_sort(out.begin(), out.end(),
                   [](const RunEvent& a, const RunEvent& b) { return a.t_s < b.t_s; });
  return out;
}

std::string run_plot_body(const std::string& title, double wheel_radius_m, int per_side,
                          const std::vector<RunEvent>& events) {
  const std::string r = fmt(wheel_radius_m);
  const std::string ref = "((column(\"ref_L_radps\")+column(\"ref_R_radps\"))/2*" + r + ")";
  std::string b = "set multiplot layout 4,1 title '" + title + "'\nset grid\nset key outside right\n";
  b += "set lmargin 10\nset rmargin 18\nset format x ''\nset autoscale xfix\n";
  b += event_lines(events, true);
  b += "set ylabel 'speed, m/s'\n";
  b += "plot 'trace.csv' using \"t_s\":\"v_x_mps\" with lines lw 2 title 'v_x', \\\n"
       "     '' using \"t_s\":" +
       ref + " with lines lw 1 dt 2 lc rgb 'black' title 'reference'\n";
  b += event_lines(events, false);
  b += "set ylabel 'agents'\nset yrange [0:" + fmt(per_side * kAgentHeadroom) + "]\n";
  b += "plot 'trace.csv' using \"t_s\":\"n_active_L\" with steps lw 2 title 'active L', \\\n"
       "     '' using \"t_s\":\"n_active_R\" with steps lw 2 title 'active R', \\\n"
       "     '' using \"t_s\":\"n_live_L\" with steps lw 2 dt 2 lc rgb 'black' title 'live L', \\\n"
       "     '' using \"t_s\":\"n_live_R\" with steps lw 2 dt 3 lc rgb 'gray40' title 'live R'\n";
  b += "set autoscale y\nset ylabel 'energy, kJ'\n";
  b += "plot 'trace.csv' using \"t_s\":(column(\"energy_J\")/1000) with lines lw 2 title 'energy'\n";
  b += "set format x '%g'\nset xlabel 'simulated time, s'\nset ylabel 'battery, V'\n";
  b += "plot 'trace.csv' using \"t_s\":\"battery_V_L\" with lines lw 2 title 'battery L', \\\n"
       "     '' using \"t_s\":\"battery_V_R\" with lines lw 2 title 'battery R'\n";
  return b + "unset multiplot\n";
}

bool draw_run_plot(const std::string& run_dir) {
  for (const char* f : {"trace.csv", "summary.json", "scenario.yaml"})
    if (!std::filesystem::exists(run_dir + "/" + f)) {
      std::fprintf(stderr, "maptr: no %s in %s: cannot draw run.png\n", f, run_dir.c_str());
      return false;
    }
  const config::Scenario sc = config::load_scenario(run_dir + "/scenario.yaml");
  const records::Summary s = records::Summary::read(run_dir + "/summary.json");
  const std::string title = sc.name + ": " + std::to_string(sc.robot.agents) + " agents, mode " + sc.mode +
                            ", status " + s.status();
  const std::string body =
      run_plot_body(title, sc.robot.wheel_radius_m, sc.robot.per_side(), run_events(s.data()));
  return draw_plot(run_dir, kStem, "run.png of " + run_dir + " (maptr plot RUN redraws it)",
                   PlotFrame{kFrameSize, ",10"}, body);
}

}  // namespace maptr::deploy::report
