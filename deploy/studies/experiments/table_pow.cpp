// table-pow: the paper's Table, NO vs EC at six gross masses (16 agents, straight line).
#include <sstream>

#include "deploy/studies/experiments/experiment_list.hpp"
#include "deploy/studies/experiments/paper.hpp"
#include "plant_core/speed_band.hpp"
#include "records/study_columns.hpp"

namespace maptr::deploy {

namespace {

struct Conditions {
  std::vector<double> masses;
  double speed, duration;
};

Conditions conditions(bool quick) {
  if (quick) return {{13.2, 38.2}, 10.0, 60.0};
  return {{13.2, 18.2, 23.2, 28.2, 33.2, 38.2}, 20.0, 1800.0};
}

json row_of(double m, const RunPair& p) {
  const Run &no = p.no, &ec = p.ec;
  json row = {{"gross_kg", m},
              {"E_NO_kJ", num(no.energy_kJ())},
              {"E_EC_kJ", num(ec.energy_kJ())},
              {"saving_pct", num(saving_pct(p))},
              {"active_EC_end", active_end_json(ec)},
              {"active_EC_mean", num(ec.trace.active_cruise)},
              {"mileage_NO", num(no.mileage())},
              {"mileage_EC", num(ec.mileage())},
              {"eff_NO", num(no.trace.eff_cruise)},
              {"eff_EC", num(ec.trace.eff_cruise)},
              {"V_over_VB_EC", num(ec.trace.v_over_vb)},
              {"v_end_NO_mps", num(no.trace.v_end_mps)},
              {"v_end_EC_mps", num(ec.trace.v_end_mps)},
              {"distance_NO_m", num(no.summary.distance_m())},
              {"distance_EC_m", num(ec.summary.distance_m())},
              {"speed_held_NO", no.speed_held()},
              {"speed_held_EC", ec.speed_held()},
              {"status_NO", no.status()},
              {"status_EC", ec.status()}};
  if (const paper::PowerRow* pr = paper::power_row(m)) {
    row["E_NO_paper_kJ"] = pr->e_no_kJ;
    row["E_EC_paper_kJ"] = pr->e_ec_kJ;
    row["saving_paper_pct"] = pr->saving_pct;
    row["active_paper"] = pr->active;
    row["mileage_NO_paper"] = pr->mileage_no;
    row["mileage_EC_paper"] = pr->mileage_ec;
  }
  return row;
}

std::string intro(const Conditions& c, bool quick) {
  std::ostringstream o;
  o << "16 agents, Type-I motors, straight line at " << c.speed << " m/s for " << c.duration
    << " s simulated (step reference from rest), battery from full (V_B(0) = 23.4 V). NO: every agent drives "
       "(the paper's baseline); EC: Levels 2 and 3. Energy is drawn from both batteries over the whole run. "
       "Mileage = distance / energy. eff: mean per-agent efficiency (mean of the two sides) over the second "
       "half "
       "of the run; V/V_B: applied voltage over battery voltage of the active agents, second half (1 = the "
       "agents are at the supply limit). v end: mean speed over the last 10% of the run."
    << (quick
            ? " Quick variant: the paper's numbers are for 1800 s at 20 m/s and are shown for reference only."
            : "");
  return o.str();
}

std::string after(const std::vector<std::string>& not_held) {
  std::ostringstream o;
  if (not_held.empty()) {
    o << "Every run held its reference speed (within " << plant_core::kSpeedBandPct << "% at the end).";
    return o.str();
  }
  o << "**Speed not held** (mean speed over the last 10% of the run more than " << plant_core::kSpeedBandPct
    << "% below the reference): ";
  for (std::size_t i = 0; i < not_held.size(); ++i) o << (i ? ", " : "") << not_held[i];
  o << ". These rows compare runs that did not cover the paper's distance; their mileage is the fair "
       "comparison.";
  return o.str();
}

void plots(Experiment& e, const Conditions& c) {
  const std::string f = "table-pow.csv";
  e.plot(
      "table-pow-energy",
      "set title 'Energy over the run, NO vs EC (16 agents, " + fixed(c.speed, 0) + " m/s, " +
          fixed(c.duration, 0) + " s)'\nset xlabel 'gross mass (kg)'\nset ylabel 'energy drawn (kJ)'\n" +
          report::plot_command({{f, "gross_kg", "E_NO_kJ", "linespoints lw 2 pt 7", "NO (this model)", ""},
                                {"", "gross_kg", "E_EC_kJ", "linespoints lw 2 pt 5", "EC (this model)", ""},
                                {"", "gross_kg", "E_NO_paper_kJ", "points pt 6 ps 2", "NO (paper)", ""},
                                {"", "gross_kg", "E_EC_paper_kJ", "points pt 4 ps 2", "EC (paper)", ""}}));
  e.plot("table-pow-saving",
         "set title 'Energy saving of EC over NO'\nset xlabel 'gross mass (kg)'\nset ylabel 'saving (%)'\n" +
             report::plot_command({{f, "gross_kg", "saving_pct", "linespoints lw 2 pt 7", "this model", ""},
                                   {"", "gross_kg", "saving_paper_pct", "points pt 6 ps 2", "paper", ""}}));
  e.plot("table-pow-active",
         "set title 'Active agents chosen by EC (L + R)'\nset xlabel 'gross mass (kg)'\nset ylabel 'active "
         "agents'\n"
         "set yrange [0:17]\n" +
             report::plot_command(
                 {{f, "gross_kg", "active_EC_end", "linespoints lw 2 pt 7", "this model (end)", ""},
                  {"", "gross_kg", "active_EC_mean", "linespoints lw 1 dt 2 pt 1",
                   "this model (mean, 2nd half)", ""},
                  {"", "gross_kg", "active_paper", "points pt 6 ps 2", "paper", ""}}));
}

}  // namespace

int exp_table_pow(Experiment& e) {
  const Conditions c = conditions(e.quick());
  e.set_total(static_cast<int>(c.masses.size()) * 2);
  records::ResultTable t;
  t.cols = records::columns::table_pow();
  std::vector<std::string> not_held;
  for (double m : c.masses) {
    config::Scenario s = e.base();
    s.robot.agents = 16;
    s.robot.gross_mass_kg = m;
    Experiment::straight(s, c.speed, c.duration);
    s.trace_every = trace_every_for(c.duration);
    const RunPair p = run_no_ec(e, s, kg_label(m) + "kg", kg_label(m) + " kg");
    if (!p.no.aborted() && !p.no.speed_held()) not_held.push_back(kg_label(m) + " kg NO");
    if (!p.ec.aborted() && !p.ec.speed_held()) not_held.push_back(kg_label(m) + " kg EC");
    t.rows.push_back(row_of(m, p));
  }
  e.write(
      t, intro(c, e.quick()), after(not_held),
      {{"conditions", {{"agents", 16}, {"speed_mps", c.speed}, {"duration_s", c.duration}, {"motor", "I"}}}});
  plots(e, c);
  return e.exit_code();
}

}  // namespace maptr::deploy
