// The EC time-series experiments (weights, voltages): one EC run per swept value, every Level-2
// decision checked against the exhaustive search, efficiency and active agents against time.
#include <filesystem>

#include "deploy/studies/experiments/experiment_list.hpp"
#include "records/study_columns.hpp"

namespace maptr::deploy {

namespace {

json row_of(const std::string& xkey, double x, const Run& r) {
  const json l2 = r.level2();
  return {{xkey, x},
          {"energy_kJ", num(r.energy_kJ())},
          {"mileage", num(r.mileage())},
          {"eff_cruise", num(r.trace.eff_cruise)},
          {"active_mean", num(r.trace.active_cruise)},
          {"active_end", active_end_json(r)},
          {"V_applied_V", num(r.trace.v_applied)},
          {"V_over_VB", num(r.trace.v_over_vb)},
          {"v_end_mps", num(r.trace.v_end_mps)},
          {"l2_decisions", l2["decisions"]},
          {"l2_solve_ms", l2.contains("solve_ms_median") ? l2["solve_ms_median"] : json(nullptr)},
          {"oracle_differs", l2["differs"]},
          {"oracle_checked", l2["checked"]},
          {"speed_held", r.speed_held()},
          {"status", r.status()}};
}

}  // namespace

int ec_time_series(Experiment& e, const std::vector<SeriesVariant>& vars, const std::string& xkey,
                   const std::string& xhead, const std::string& intro, const std::string& what) {
  e.set_total(static_cast<int>(vars.size()));
  records::ResultTable t;
  t.cols = records::columns::ec_series(xkey, xhead);
  std::vector<std::pair<std::string, std::string>> files;
  std::filesystem::create_directories(e.dir() + "/series");
  for (const auto& v : vars) {
    config::Scenario sv = v.s;
    sv.control.oracle = true;  // every Level-2 decision is checked against the exhaustive search
    const Run r = e.run(v.id, v.label, sv);
    if (!r.aborted()) {
      write_series(r, e.dir() + "/series/" + v.id + ".csv", bin_for(v.s.duration_s));
      files.push_back({v.id, v.label});
    }
    t.rows.push_back(row_of(xkey, v.x, r));
  }
  e.write(t,
          intro +
              " Level 2 runs at 1 Hz per side; every decision was also solved by the exhaustive search "
              "(the oracle), and 'Ipopt != oracle' counts the decisions where Ipopt's integer differed.",
          "");
  if (files.empty()) return e.exit_code();
  e.plot(e.opt().name + "-efficiency", "set title 'Per-agent efficiency, EC, " + what +
                                           "'\nset xlabel 'time (s)'\n"
                                           "set ylabel 'efficiency of an active agent (mean of L and R)'\n"
                                           "set yrange [0:1]\n" +
                                           series_plot(files, "eff_agent"));
  e.plot(e.opt().name + "-active",
         "set title 'Active agents (L + R), EC, " + what +
             "'\nset xlabel 'time (s)'\nset ylabel 'active agents'\nset yrange [0:*]\n" +
             series_plot(files, "n_active"));
  return e.exit_code();
}

}  // namespace maptr::deploy
