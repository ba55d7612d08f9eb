// faults: every way an agent breaks while it runs on (docs/ARCHITECTURE.md "Fault detection"),
// on 1, 2 and 4 agents of side L of the warehouse loop at 13.2 and 30 kg, with the groups'
// detection on and off, against a fault-free twin; the crash of the same agents (a kill, which
// the plant's membership detects) for comparison.
#include <algorithm>
#include <sstream>

#include "deploy/studies/experiments/experiment_list.hpp"
#include "records/study_columns.hpp"

namespace maptr::deploy {

namespace {

constexpr int kAgents = 16, kPerSide = kAgents / 2;

struct Mode {
  const char* mode;  ///< "kill": the crash
  double value;
};

struct Conditions {
  std::vector<double> masses;
  std::vector<int> counts;
  std::vector<Mode> modes;
  double fault_at = 20.0, duration = 0.0;
};

Conditions conditions(bool q) {
  Conditions c;
  c.masses = q ? std::vector<double>{30.0} : std::vector<double>{13.2, 30.0};
  c.counts = q ? std::vector<int>{1} : std::vector<int>{1, 2, 4};
  c.modes =
      q ? std::vector<Mode>{{"open", 0}, {"sensor", 5}, {"kill", 0}}
        : std::vector<Mode>{{"open", 0},   {"short", 0},   {"torque", 0.5}, {"resistance", 3}, {"stuck", 12},
                            {"sensor", 5}, {"erratic", 2}, {"liar", 0},     {"kill", 0}};
  c.duration = q ? 30.0 : 0.0;  // 0: the loop's own (the default scenario's)
  return c;
}

std::string mode_label(const Mode& m) {
  return m.value != 0.0 ? std::string(m.mode) + "=" + kg_label(m.value) : std::string(m.mode);
}

config::Scenario scenario(const Experiment& e, const Conditions& c, double mass, bool detection) {
  config::Scenario s =
      config::load_scenario(e.opt().source_dir + "/deploy/scenarios/default.yaml");  // the loop
  s.tick_hz = e.tick_hz();
  s.robot.agents = kAgents;
  s.robot.gross_mass_kg = mass;
  s.mode = "ec";
  if (c.duration > 0.0) s.duration_s = c.duration;
  s.control.fault_detection = detection;
  s.trace_every = 10;
  return s;
}

config::Scenario faulty(config::Scenario s, const Conditions& c, const Mode& m,
                        const std::vector<int>& targets) {
  for (const int j : targets) {
    config::FaultSpec f;
    f.target = config::agent_name(0, j);
    f.at_s = c.fault_at;
    if (std::string(m.mode) == "kill") {
      f.action = "kill";
    } else {
      f.action = "fault";
      f.mode = m.mode;
      f.value = m.value;
    }
    s.faults.push_back(f);
  }
  return s;
}

/// When the trajectory's closing stop starts (the run's end if it has none), s.
double stop_start(const config::Scenario& s) {
  double t = 0.0;
  for (const auto& seg : s.trajectory.segments) {
    if (seg.type == "stop") return std::min(t, s.duration_s);
    t += seg.duration_s;
  }
  return s.duration_s;
}

/// The run's record of each fault it was given: detection and isolation delays (s after the
/// fault), diagnoses.
void add_detection(json& row, const Run& r, const Conditions& c) {
  int detected = 0;
  double det_max = kNaN, iso_max = kNaN;
  std::vector<std::string> diagnosed;
  for (const auto& f : r.summary.failures_json()) {
    if (f.value("at_s", -1.0) < c.fault_at - 1e-9) continue;
    const bool kill = f.value("action", "") == "kill";
    if (!kill && f.value("action", "") != "fault") continue;
    if (f.contains("detected_s") && f["detected_s"].is_number()) {
      ++detected;
      const double d = f["detected_s"].get<double>() - c.fault_at;
      det_max = std::isfinite(det_max) ? std::max(det_max, d) : d;
      // A kill is out of the count from the tick its death is seen; a fault from the next.
      const double iso = kill ? d : f.value("isolated_s", f["detected_s"].get<double>()) - c.fault_at;
      iso_max = std::isfinite(iso_max) ? std::max(iso_max, iso) : iso;
    }
    if (!kill && f.contains("diagnosed_mode") && f["diagnosed_mode"].is_string())
      diagnosed.push_back(f["diagnosed_mode"].get<std::string>());
  }
  std::sort(diagnosed.begin(), diagnosed.end());
  diagnosed.erase(std::unique(diagnosed.begin(), diagnosed.end()), diagnosed.end());
  std::string d;
  for (const auto& x : diagnosed) d += (d.empty() ? "" : " ") + x;
  row["detected"] = detected;
  row["detect_s_max"] = num(det_max);
  row["isolate_s_max"] = num(iso_max);
  row["diagnosed"] = d;
}

json row_of(const Run& r, const Run& twin, const Conditions& c, double mass, int k, std::size_t mi,
            bool detection) {
  const Mode& m = c.modes[mi];
  json row = {{"mass_kg", mass},
              {"agents", k},
              {"mode", mode_label(m)},
              {"mode_index", static_cast<int>(mi)},
              {"detection", std::string(m.mode) == "kill" ? "plant" : (detection ? "on" : "off")},
              {"status", r.status()}};
  if (r.aborted()) return row;
  add_detection(row, r, c);
  row["max_speed_error_pct"] = num(max_speed_error_after(r, c.fault_at));
  row["cross_track_max_m"] = num(r.summary.data()
                                     .value("plant", json::object())
                                     .value("path", json::object())
                                     .value("cross_track_max_m", kNaN));
  row["energy_kJ"] = num(r.energy_kJ());
  // The loop ends on a step from 1 m/s to 0 that every live agent brakes by driving backwards at
  // its limit: the stop's energy grows with the number of live agents, so the penalty is read
  // before it, and over the whole run apart.
  const double until = stop_start(r.s);
  row["energy_penalty_J"] =
      twin.aborted() ? json(nullptr) : num(energy_at(r, until) - energy_at(twin, until));
  row["energy_penalty_run_J"] =
      twin.aborted() ? json(nullptr) : num(1000.0 * (r.energy_kJ() - twin.energy_kJ()));
  return row;
}

std::string intro(const Conditions& c) {
  std::ostringstream o;
  o << "EC, 16 agents, the warehouse loop (deploy/scenarios/default.yaml: bidirectional driver). At t = "
    << c.fault_at
    << " s, on the first straight at 1 m/s, k agents of side L break: those driving at that moment in the "
       "fault-free twin first. Each mode as `maptr run --fault L3:MODE[=VALUE]@20` gives it; `kill` is the "
       "crash "
       "(SIGKILL), which the plant's membership detects. 'detection on': the groups check every agent "
       "against "
       "the drive's measurements and isolate it (control.fault_detection); 'off': the fault runs silent. "
       "Detection and isolation are in s after the fault (the latest of the k agents); 'diagnosed as' lists "
       "what the groups took the faults for; 'max speed error' is the largest deviation from the reference "
       "from the fault to the end; 'path error' the largest cross-track error of the run; the energy penalty "
       "is the energy drawn minus that of the fault-free twin at the same mass, up to the start of the "
       "loop's closing stop (63.6 s), and over the whole run: the stop is a step from 1 m/s to 0 that "
       "every live agent brakes by driving backwards at its limit, so an agent out of the fleet makes the "
       "stop cheaper by about its share.";
  return o.str();
}

void plots(Experiment& e, const Conditions& c) {
  const double mass = c.masses.back();
  // The rows of one faulty agent at this mass with this detection.
  const auto one = [mass](const char* detection) {
    return "(column('agents')==1 && column('mass_kg')==" + fixed(mass, 1) + " && strcol('detection') eq '" +
           detection + "')";
  };
  const auto x_of = [](const std::string& rows, const char* shift) {
    return "(" + rows + " ? column('mode_index')" + shift + " : NaN)";
  };
  std::string xtics;
  for (std::size_t i = 0; i < c.modes.size(); ++i)
    xtics += (xtics.empty() ? "" : ", ") + ("'" + mode_label(c.modes[i]) + "' " + std::to_string(i));
  const std::string common = "set xtics rotate by -25 (" + xtics +
                             ")\nset xrange [-0.5:" + std::to_string(c.modes.size()) +
                             "-0.5]\nset key inside top left\nset grid ytics\n";
  e.plot("faults-energy",
         "set title 'One broken agent: energy penalty before the stop (EC, 16 agents, " + kg_label(mass) +
             " kg, warehouse loop)'\nset ylabel 'energy drawn minus the fault-free run (J)'\n" + common +
             "plot 'faults.csv' using " + x_of(one("on"), "-0.1") +
             ":'energy_penalty_J' with points pt 7 ps 1.5 title 'detection on', \\\n"
             "     '' using " +
             x_of(one("off"), "+0.1") +
             ":'energy_penalty_J' with points pt 5 ps 1.5 title 'detection off', \\\n"
             "     '' using " +
             x_of(one("plant"), "") + ":'energy_penalty_J' with points pt 9 ps 1.8 title 'crash (kill)'\n");
  const std::string seen = "(" + one("on") + " || " + one("plant") + ")";
  e.plot("faults-detection",
         "set title 'One broken agent: detection and isolation (EC, 16 agents, " + kg_label(mass) +
             " kg)'\nset ylabel 'simulated s after the fault'\nset yrange [0:*]\n" + common +
             "plot 'faults.csv' using " + x_of(seen, "") +
             ":'detect_s_max' with points pt 7 ps 1.5 title 'detected', \\\n"
             "     '' using " +
             x_of(seen, "") + ":'isolate_s_max' with points pt 6 ps 2 title 'isolated'\n");
}

}  // namespace

int exp_faults(Experiment& e) {
  const Conditions c = conditions(e.quick());
  int total = 0;
  for (std::size_t mi = 0; mi < c.modes.size(); ++mi)
    total += std::string(c.modes[mi].mode) == "kill" ? 1 : 2;
  e.set_total(static_cast<int>(c.masses.size() * (1 + c.counts.size() * static_cast<std::size_t>(total))));
  records::ResultTable t;
  t.cols = records::columns::faults();
  for (const double mass : c.masses) {
    const Run twin =
        e.run("twin-" + kg_label(mass), kg_label(mass) + " kg fault-free", scenario(e, c, mass, true));
    const DrivingOrder order = twin.aborted() ? DrivingOrder{} : driving_first(twin, c.fault_at, kPerSide);
    for (const int k : c.counts) {
      std::vector<int> targets;
      for (int j = 0; j < k; ++j)
        targets.push_back(order[0].size() > static_cast<std::size_t>(j) ? order[0][j] : j);
      for (std::size_t mi = 0; mi < c.modes.size(); ++mi) {
        const Mode& m = c.modes[mi];
        const bool kill = std::string(m.mode) == "kill";
        for (const bool detection : {true, false}) {
          if (kill && !detection) continue;
          const std::string id = kg_label(mass) + "kg-" + std::to_string(k) + "-" + m.mode +
                                 (kill        ? ""
                                  : detection ? "-on"
                                              : "-off");
          const Run r = e.run(id,
                              kg_label(mass) + " kg, " + std::to_string(k) + " x " + mode_label(m) +
                                  (kill        ? ""
                                   : detection ? ", detection on"
                                               : ", detection off"),
                              faulty(scenario(e, c, mass, detection), c, m, targets));
          t.rows.push_back(row_of(r, twin, c, mass, k, mi, detection));
          if (e.stopped()) break;
        }
      }
    }
  }
  e.write(t, intro(c), "", {{"fault_at_s", c.fault_at}});
  plots(e, c);
  return e.exit_code();
}

}  // namespace maptr::deploy
