// agents: the energy advantage of EC over NO against the number of agents.
#include <sstream>

#include "deploy/studies/experiments/experiment_list.hpp"
#include "records/study_columns.hpp"

namespace maptr::deploy {

namespace {

struct Series {
  std::string key, label;
  double per_agent_kg;  ///< > 0: gross = per_agent_kg * N
  double fixed_kg;      ///< otherwise this gross mass
};

struct Conditions {
  std::vector<int> ns;
  std::vector<Series> series;
  double speed, duration;
};

Conditions conditions(bool q) {
  if (q) return {{8, 16}, {{"1.5kg-per-agent", "1.5 kg/agent", 1.5, 0}}, 10.0, 30.0};
  return {{8, 16, 32, 64, 128},
          {{"0.8kg-per-agent", "0.8 kg/agent", 0.8, 0},
           {"1.5kg-per-agent", "1.5 kg/agent", 1.5, 0},
           {"2.2kg-per-agent", "2.2 kg/agent", 2.2, 0},
           {"13.2kg-fixed", "13.2 kg for every N", 0, 13.2}},
          10.0,
          120.0};
}

json row_of(const Series& se, int n, double gross, const RunPair& p) {
  return {{"series", se.label},
          {"agents", n},
          {"gross_kg", gross},
          {"E_NO_kJ", num(p.no.energy_kJ())},
          {"E_EC_kJ", num(p.ec.energy_kJ())},
          {"saving_pct", num(saving_pct(p))},
          {"active_EC_end", active_end_json(p.ec)},
          {"active_EC_mean", num(p.ec.trace.active_cruise)},
          {"eff_NO", num(p.no.trace.eff_cruise)},
          {"eff_EC", num(p.ec.trace.eff_cruise)},
          {"status_NO", p.no.status()},
          {"status_EC", p.ec.status()}};
}

std::string intro(const Conditions& c, bool q) {
  std::ostringstream o;
  o << "NO vs EC for N in {";
  for (std::size_t i = 0; i < c.ns.size(); ++i) o << (i ? ", " : "") << c.ns[i];
  o << "} agents, straight line at " << c.speed << " m/s for " << c.duration
    << " s simulated (acceleration from rest included), Type-I motors. Payload series: the gross mass scaled "
       "with "
       "N (kg per agent: the same load per motor at every N)"
    << (q ? "."
          : ", and one fixed gross mass of 13.2 kg for every N (the same robot load spread over more "
            "motors).")
    << (q ? " The full run goes up to 128 agents (132 processes per fleet)." : "");
  return o.str();
}

void plots(Experiment& e, const Conditions& c) {
  const std::string when = fixed(c.speed, 0) + " m/s, " + fixed(c.duration, 0) + " s)'";
  std::string p = "plot ";
  for (std::size_t i = 0; i < c.series.size(); ++i)
    p += (i ? ", \\\n     " : "") + std::string("'agents.csv' using \"agents\":(strcol(\"series\") eq '") +
         c.series[i].label + "' ? column(\"saving_pct\") : NaN) with linespoints lw 2 pt " +
         std::to_string(5 + 2 * i) + " title '" + c.series[i].label + "'";
  e.plot("agents-saving",
         "set title 'Energy advantage of EC over NO vs number of agents (" + when +
             "\nset xlabel 'agents N'\nset ylabel 'saving (%)'\nset logscale x 2\nset xrange [" +
             fixed(c.ns.front() * 0.75, 0) + ":" + fixed(c.ns.back() * 1.25, 0) + "]\nset yrange [0:*]\n" +
             p + "\n");
  // The paper's form of the figure: saving against the load, one curve per N (a flatter curve
  // keeps the advantage over a wider range of payloads). Rows are series-major, so the rows of
  // the i-th N are every ns.size()-th row from row i.
  std::string pm = "plot ";
  for (std::size_t i = 0; i < c.ns.size(); ++i)
    pm += (i ? ", \\\n     " : "") + std::string("'agents.csv' every ") + std::to_string(c.ns.size()) +
          "::" + std::to_string(i) +
          " using \"gross_kg\":\"saving_pct\" smooth unique with linespoints lw 2 pt " +
          std::to_string(5 + 2 * static_cast<int>(i)) + " title 'N = " + std::to_string(c.ns[i]) + "'";
  e.plot("agents-saving-vs-mass",
         "set title 'Energy advantage of EC over NO vs gross mass, per number of agents (" + when +
             "\nset xlabel 'gross mass (kg)'\nset ylabel 'saving (%)'\n"
             "set logscale x 2\nset yrange [0:*]\n" +
             pm + "\n");
}

}  // namespace

int exp_agents(Experiment& e) {
  const Conditions c = conditions(e.quick());
  e.set_total(static_cast<int>(c.ns.size() * c.series.size() * 2));
  records::ResultTable t;
  t.cols = records::columns::agents();
  for (const auto& se : c.series)
    for (int n : c.ns) {
      const double gross = se.per_agent_kg > 0 ? se.per_agent_kg * n : se.fixed_kg;
      config::Scenario s = e.base();
      s.robot.agents = n;
      s.robot.gross_mass_kg = gross;
      Experiment::straight(s, c.speed, c.duration);
      s.trace_every = trace_every_for(c.duration);
      const RunPair p = run_no_ec(e, s, se.key + "-N" + std::to_string(n),
                                  "N=" + std::to_string(n) + " " + kg_label(gross) + " kg");
      t.rows.push_back(row_of(se, n, gross, p));
    }
  e.write(t, intro(c, e.quick()), "");
  plots(e, c);
  return e.exit_code();
}

}  // namespace maptr::deploy
