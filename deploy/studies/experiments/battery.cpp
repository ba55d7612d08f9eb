// battery: NO vs EC from the same charge until the speed can no longer be held.
#include <filesystem>
#include <sstream>

#include "deploy/studies/experiments/experiment_list.hpp"
#include "deploy/studies/experiments/paper.hpp"
#include "records/study_columns.hpp"

namespace maptr::deploy {

namespace {

struct Conditions {
  double gross = 34.4, speed = 15.0;
  double initial_mAh, duration;
  int trace_every;
  double bin_s;
};

/// Quick: from 6000 mAh (V_B = 20.45 V), a few hundred seconds before the knee of the discharge
/// curve where 15 m/s can no longer be held (about 18.2 V).
Conditions conditions(bool q) {
  Conditions c;
  c.initial_mAh = q ? 6000.0 : 0.0;
  c.duration = q ? 1500.0 : 30000.0;
  c.trace_every = q ? 10 : 100;
  c.bin_s = q ? 2.0 : 60.0;
  return c;
}

/// The speed falls more than this far below its reference for 5 s: the run ends.
constexpr double kStopBelowSpeedPct = 5.0;

/// What a run gives: how long it lasted and whether it ended by losing its speed.
struct Outcome {
  double lasted = kNaN;
  bool by_speed = false;
};

json row_of(const char* mode, const Run& r, const Outcome& o) {
  namespace k = records::summary_key;
  const double vb = 0.5 * (r.summary.plant_side(k::kBatteryV, "L") + r.summary.plant_side(k::kBatteryV, "R"));
  return {{"mode", mode},
          {"lasted_s", num(o.lasted)},
          {"distance_km", num(r.summary.distance_m() / 1000.0)},
          {"energy_kJ", num(r.energy_kJ())},
          {"mileage", num(r.mileage())},
          {"drawn_mAh", num(r.summary.plant_side(k::kDischarge, "L"))},
          {"battery_V_end", num(vb)},
          {"eff_mean", num(r.trace.eff_cruise)},
          {"active_mean", num(r.trace.active_cruise)},
          {"ended_by_speed_loss", o.by_speed},
          {"end_reason", r.summary.end_reason()},
          {"status", r.status()}};
}

std::string intro(const Conditions& c) {
  std::ostringstream o;
  o << "16 agents, Type-I motors, 30 kg payload: gross mass " << c.gross
    << " kg (payload + 4.4 kg of robot), straight line at " << c.speed
    << " m/s, battery 6395 mAh per side starting at " << c.initial_mAh
    << " mAh discharged. Each run ends when the speed has stayed more than 5% below the reference for 5 s "
       "(stop_below_speed_pct: 5) or at "
    << c.duration << " s simulated. 'lasted' is the simulated time at the end (it includes those 5 s).";
  return o.str();
}

std::string after(const Outcome o[2]) {
  const double diff = o[1].lasted - o[0].lasted;
  if (!std::isfinite(diff)) return "";
  std::ostringstream a;
  a << "**EC lasted " << fixed(diff, 0) << " s " << (diff >= 0 ? "longer" : "shorter") << " than NO** ("
    << fixed(o[1].lasted, 0) << " s vs " << fixed(o[0].lasted, 0) << " s"
    << (o[0].by_speed && o[1].by_speed ? "" : "; at least one run did not end by losing its speed")
    << "). Paper: about " << fixed(paper::kBatteryEcLongerS, 0)
    << " s longer (6395 mAh, 30 kg payload, speed not stated).";
  return a.str();
}

void plots(Experiment& e, const Conditions& c,
           const std::vector<std::pair<std::string, std::string>>& files) {
  const std::string what = fixed(c.gross, 1) + " kg, " + fixed(c.speed, 0) + " m/s";
  e.plot("battery-voltage",
         "set title 'Battery voltage, NO vs EC (" + what +
             ")'\nset xlabel 'time (s)'\nset ylabel 'battery voltage (V, mean of L and R)'\n" +
             series_plot(files, "battery_V"));
  e.plot("battery-speed",
         "set title 'Speed, NO vs EC (" + what +
             " reference)'\nset xlabel 'time (s)'\nset ylabel 'speed (m/s)'\nset yrange [0:*]\n" +
             series_plot(files, "v_x_mps"));
  e.plot("battery-active",
         "set title 'Active agents (L + R), NO vs EC'\nset xlabel 'time (s)'\n"
         "set ylabel 'active agents'\nset yrange [0:17]\n" +
             series_plot(files, "n_active"));
  e.plot("battery-efficiency",
         "set title 'Per-agent efficiency, NO vs EC'\nset xlabel 'time (s)'\n"
         "set ylabel 'efficiency of an active agent'\nset yrange [0:1]\n" +
             series_plot(files, "eff_agent"));
}

}  // namespace

int exp_battery(Experiment& e) {
  const Conditions c = conditions(e.quick());
  e.set_total(2);
  records::ResultTable t;
  t.cols = records::columns::battery();
  std::vector<std::pair<std::string, std::string>> files;
  std::filesystem::create_directories(e.dir() + "/series");
  Outcome out[2];
  for (int k = 0; k < 2; ++k) {
    config::Scenario s = e.base();
    s.robot.agents = 16;
    s.robot.gross_mass_kg = c.gross;
    s.mode = k == 0 ? "all" : "ec";
    s.initial_discharge_mAh = c.initial_mAh;
    s.stop_below_speed_pct = kStopBelowSpeedPct;
    Experiment::straight(s, c.speed, c.duration);
    s.trace_every = c.trace_every;
    const std::string id = k == 0 ? "no" : "ec";
    const char* mode = k == 0 ? "NO" : "EC";
    const Run r = e.run(id, mode, s);
    if (!r.aborted()) {
      write_series(r, e.dir() + "/series/" + id + ".csv", c.bin_s);
      files.push_back({id, mode});
      out[k].lasted = r.sim_s();
    }
    out[k].by_speed = r.summary.end_reason().find("below its reference") != std::string::npos;
    t.rows.push_back(row_of(mode, r, out[k]));
  }
  e.write(t, intro(c), after(out), {{"ec_minus_no_s", num(out[1].lasted - out[0].lasted)}});
  if (!files.empty()) plots(e, c, files);
  return e.exit_code();
}

}  // namespace maptr::deploy
