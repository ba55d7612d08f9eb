// turns: what turns the robot can hold and what EC does on a path with turns.
//   (a) reach: the tightest radius against speed (model::tightest_radius, a steady turn with
//       every agent active, full battery) for the unidirectional and bidirectional drivers at
//       three gross masses: turns-reach.csv, turns-reach.md, turns-reach.png. No fleet.
//   (b) the warehouse loop (deploy/scenarios/default.yaml, 30 kg, bidirectional driver), NO
//       against EC on the fleet: turns.csv, turns.md, series/ and the energy and active plots.
// --quick: fewer speeds in (a); in (b) the loop's straights are shortened (5, 4 and 5 m).
#include <cmath>
#include <filesystem>
#include <sstream>

#include "deploy/studies/experiments/experiment_list.hpp"
#include "model/battery.hpp"
#include "model/motor.hpp"
#include "model/reach.hpp"
#include "records/run_files.hpp"
#include "records/study_columns.hpp"
#include "records/trace.hpp"

namespace maptr::deploy {

namespace {

const std::vector<double> kMasses = {13.2, 30.0, 38.2};
const std::vector<std::string> kDrivers = {"unidirectional", "bidirectional"};

std::vector<double> reach_speeds(bool quick) {
  if (quick) return {0.5, 1.0, 5.0, 10.0};
  return {0.25, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.0, 14.0, 16.0, 18.0, 20.0};
}

std::string reach_key(const std::string& driver, double kg) {
  return std::string(driver == "bidirectional" ? "R_bi_" : "R_uni_") + kg_label(kg) + "kg_m";
}

/// The loop's scenario with its driver and gross mass set.
config::Scenario loop_scenario(const Experiment& e) {
  config::Scenario s = config::load_scenario(e.opt().source_dir + "/deploy/scenarios/default.yaml");
  s.tick_hz = e.tick_hz();
  return s;
}

/// A radius as JSON: a number, "any" below kMinReachRadius, null when none is held.
json radius_json(double rmin) {
  if (std::isinf(rmin)) return nullptr;
  return rmin;
}

records::ResultTable reach_table(const config::Scenario& base, const std::vector<double>& speeds,
                                 double battery_V) {
  records::ResultTable t;
  t.cols = {{"speed_mps", "speed m/s", 2}};
  for (const auto& d : kDrivers)
    for (double m : kMasses)
      t.cols.push_back({reach_key(d, m),
                        std::string(d == "bidirectional" ? "bi" : "uni") + " " + kg_label(m) + " kg: R_min m",
                        3});
  for (double v : speeds) {
    json row = {{"speed_mps", v}};
    for (const auto& d : kDrivers)
      for (double m : kMasses) {
        model::RobotParams r = base.robot;
        r.driver.bidirectional = d == "bidirectional";
        r.gross_mass_kg = m;
        row[reach_key(d, m)] = radius_json(model::tightest_radius(r, v, battery_V));
      }
    t.rows.push_back(row);
  }
  return t;
}

/// The curves of the reach table, a colour per mass, dashed for the unidirectional driver, and
/// the lateral-friction bound v^2 / (mu_l g) that no driver can beat.
void reach_plot(Experiment& e, const model::RobotParams& r) {
  std::vector<report::Curve> curves;
  const char* points[] = {"7", "5", "9"};
  const char* colours[] = {"#7b3294", "#008837", "#2166ac"};
  for (const auto& d : kDrivers)
    for (std::size_t i = 0; i < kMasses.size(); ++i)
      curves.push_back({curves.empty() ? "turns-reach.csv" : "", "speed_mps", reach_key(d, kMasses[i]),
                        std::string("linespoints lw 2 pt ") + points[i] + " lc rgb '" + colours[i] + "'" +
                            (d == "bidirectional" ? "" : " dt 2"),
                        d + ", " + kg_label(kMasses[i]) + " kg", ""});
  std::string cmd = report::plot_command(curves);
  cmd.pop_back();  // its newline: the friction bound follows
  const std::string mu_g = fixed(r.mu_lateral * r.gravity, 4);
  e.plot("turns-reach",
         "set title 'Tightest steady turn against speed (16 agents, Type I, full battery)'\n"
         "set xlabel 'speed (m/s)'\nset ylabel 'tightest radius (m), log scale'\nset logscale y\n"
         "set key outside right top\nset samples 200\n" +
             cmd + ", \\\n     x**2/" + mu_g + " with lines lw 1 dt 3 lc rgb 'black' title 'v^2/(mu_l g)'\n");
}

/// Part (a): the reach table, its markdown and its plot.
json reach(Experiment& e) {
  const config::Scenario base = loop_scenario(e);
  const double battery_V = model::battery_voltage(base.robot.battery, base.initial_discharge_mAh);
  const records::ResultTable t = reach_table(base, reach_speeds(e.quick()), battery_V);
  t.write_csv(e.dir() + "/turns-reach.csv");
  std::ostringstream md;
  md << "# turns: reach" << (e.quick() ? " (quick)" : "") << "\n\nCommand: `" << e.command() << "`\n\n"
     << "The tightest radius the robot holds in a steady turn at each speed (`model::tightest_radius`, as "
        "`maptr reach` prints it): "
     << base.robot.agents << " agents, Type-I motors, every agent of each side active, battery full (V_B "
     << fixed(battery_V, 2) << " V), steady turns within " << fixed(100 * model::kReachVoltageShare, 0)
     << " % of V_B, lateral acceleration within mu_l g. uni: the unidirectional driver (0 to V_B, cannot "
        "brake: the inner side of a tight turn is dragged); bi: the bidirectional driver (an H-bridge). "
        "'–': not even a straight line is held at that speed; 0: every radius down to "
     << model::kMinReachRadius << " m.\n\n"
     << t.md();
  records::write_text_file(e.dir() + "/turns-reach.md", md.str());
  reach_plot(e, base.robot);
  return {{"battery_V", battery_V}, {"rows", t.rows}};
}

/// The quick loop: the default's straights shortened to 5, 4 and 5 m (the turns unchanged).
void shorten(config::Scenario& s) {
  const double straights[] = {6.0, 4.0, 5.0};
  int k = 0;
  double total = 0;
  for (auto& seg : s.trajectory.segments) {
    if (seg.type == "straight" && k < 3) seg.duration_s = straights[k++];
    total += seg.duration_s;
  }
  s.duration_s = std::floor(total);
}

double path_figure(const Run& r, const char* key) {
  const json p = r.summary.data().value("path", json::object());
  return r.aborted() || !p.contains(key) || !p[key].is_number() ? kNaN : p[key].get<double>();
}

json loop_row(const std::string& mode, const Run& r) {
  return {{"mode", mode},
          {"energy_kJ", num(r.energy_kJ())},
          {"mileage", num(r.mileage())},
          {"distance_m", num(r.aborted() ? kNaN : r.summary.distance_m())},
          {"active_mean", num(r.summary.number_or("mean_active_agents", kNaN))},
          {"cross_track_max_m", num(path_figure(r, "cross_track_max_m"))},
          {"cross_track_rms_m", num(path_figure(r, "cross_track_rms_m"))},
          {"heading_error_max_rad", num(path_figure(r, "heading_error_max_rad"))},
          {"final_position_error_m", num(path_figure(r, "final_position_error_m"))},
          {"status", r.status()},
          {"trace_sha256", r.summary.data().value(records::summary_key::kTraceSha, "")}};
}

/// series/loop-difference.csv: E_EC - E_NO (J) and the active agents of each mode at the trace
/// rows both runs wrote (the two runs tick alike); false when a trace is missing.
bool write_difference(const RunPair& p, const std::string& path) {
  std::vector<records::TraceRow> no, ec;
  try {
    no = records::read_trace(records::trace_path(p.no.dir));
    ec = records::read_trace(records::trace_path(p.ec.dir));
  } catch (const std::exception&) {
    return false;
  }
  records::ResultTable d;
  d.cols = {{"t_s", "t (s)", 3},
            {"dE_J", "E_EC - E_NO (J)", 3},
            {"active_NO", "active NO", 0},
            {"active_EC", "active EC", 0}};
  for (std::size_t i = 0; i < no.size() && i < ec.size(); ++i)
    d.rows.push_back({{"t_s", no[i].t_s},
                      {"dE_J", ec[i].energy_J - no[i].energy_J},
                      {"active_NO", no[i].n_active_L + no[i].n_active_R},
                      {"active_EC", ec[i].n_active_L + ec[i].n_active_R}});
  d.write_csv(path);
  return true;
}

void difference_plot(Experiment& e, const RunPair& p) {
  if (!write_difference(p, e.dir() + "/series/loop-difference.csv")) return;
  e.plot("turns-difference",
         "set title 'EC minus NO on the warehouse loop: energy drawn and active agents'\n"
         "set xlabel 'time (s)'\nset ylabel 'E_EC - E_NO (J)'\nset y2label 'active agents (L + R)'\n"
         "set y2range [0:17]\nset ytics nomirror\nset y2tics\nset key inside right bottom\n" +
             report::plot_command(
                 {{"series/loop-difference.csv", "t_s", "dE_J", "lines lw 2 lc rgb '#c0392b'", "E_EC - E_NO",
                   ""},
                  {"", "t_s", "active_EC", "steps lw 1 lc rgb '#008837'", "active EC (right axis)", "x1y2"},
                  {"", "t_s", "active_NO", "steps lw 1 dt 2 lc rgb 'black'", "active NO (right axis)",
                   "x1y2"}}));
}

void loop_plots(Experiment& e, const RunPair& p) {
  std::vector<std::pair<std::string, std::string>> files;
  for (const Run* r : {&p.no, &p.ec})
    if (!r->aborted()) {
      write_series(*r, e.dir() + "/series/" + r->id + ".csv", bin_for(r->s.duration_s));
      files.push_back({r->id, r->label});
    }
  if (files.empty()) return;
  e.plot("turns-energy",
         "set title 'Energy drawn on the warehouse loop, NO vs EC (30 kg, 1 m/s)'\n"
         "set xlabel 'time (s)'\nset ylabel 'energy (kJ)'\nset key inside left top\n" +
             series_plot(files, "energy_kJ"));
  e.plot("turns-active",
         "set title 'Active agents (L + R) on the warehouse loop'\n"
         "set xlabel 'time (s)'\nset ylabel 'active agents'\nset yrange [0:17]\n" +
             series_plot(files, "n_active", "steps lw 2"));
  difference_plot(e, p);
}

std::string loop_intro(const config::Scenario& s, bool quick) {
  std::ostringstream o;
  o << "Part (b): the warehouse loop of deploy/scenarios/default.yaml"
    << (quick ? ", its straights shortened to 5, 4 and 5 m (quick)" : "") << ": " << s.robot.agents
    << " agents, Type-I motors, " << s.robot.driver.name() << " driver, " << kg_label(s.robot.gross_mass_kg)
    << " kg gross, 1 m/s with two 90-degree turns of radius 4 m (left, then right), " << s.duration_s
    << " s simulated, central following the path in closed loop. NO: every agent drives; EC: Levels 2 "
       "and 3. active: the mean number of active agents over the run (summary.json mean_active_agents). "
       "Cross-track and heading figures: summary.json `path`. Part (a), the tightest radius against speed, "
       "is in turns-reach.md.";
  return o.str();
}

}  // namespace

int exp_turns(Experiment& e) {
  const json reach_json = reach(e);
  e.set_total(2);
  config::Scenario s = loop_scenario(e);
  s.robot.gross_mass_kg = 30.0;
  if (e.quick()) shorten(s);
  std::filesystem::create_directories(e.dir() + "/series");
  const RunPair p = run_no_ec(e, s, "loop", "loop");
  records::ResultTable t;
  t.cols = records::columns::turn_loops();
  t.rows = {loop_row("NO", p.no), loop_row("EC", p.ec)};
  std::ostringstream after;
  after << "EC against NO: energy " << fixed(p.ec.energy_kJ() - p.no.energy_kJ(), 3) << " kJ ("
        << fixed(-saving_pct(p), 2) << " %).";
  e.write(
      t, loop_intro(s, e.quick()), after.str(),
      {{"reach", reach_json},
       {"conditions", {{"agents", s.robot.agents}, {"gross_kg", 30.0}, {"driver", s.robot.driver.name()}}}});
  loop_plots(e, p);
  return e.exit_code();
}

}  // namespace maptr::deploy
