#include "deploy/studies/experiments/compare.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "deploy/fleet/isolated_launch.hpp"
#include "deploy/studies/experiments/experiment.hpp"
#include "records/study_columns.hpp"

namespace maptr::deploy {

namespace {

/// One --set: the field and its values.
struct Sweep {
  std::string option, field;
  std::vector<std::string> values;
};

Sweep parse_set(const std::string& text) {
  Sweep w;
  w.option = "--set " + text.substr(0, 120);
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw config::ScenarioError(
        w.option + ": expected FIELD=V1,V2,... (e.g. mode=ec,all; `maptr fields` lists the fields)");
  w.field = text.substr(0, eq);
  std::stringstream ss(text.substr(eq + 1));
  for (std::string v; std::getline(ss, v, ',');) {
    if (v.empty()) throw config::ScenarioError(w.option + ": an empty value between commas");
    w.values.push_back(v);
  }
  return w;
}

/// A folder name made of the field's last part and the value: "mode-ec", "gross_mass_kg-20".
std::string id_part(const std::string& field, const std::string& value) {
  std::string id =
      field.substr(field.rfind('.') == std::string::npos ? 0 : field.rfind('.') + 1) + "-" + value;
  for (char& ch : id)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_' && ch != '.') ch = '_';
  return id;
}

/// A row's number, NaN when the run did not give it (null).
double figure(const json& row, const char* key) {
  return row[key].is_number() ? row[key].get<double>() : kNaN;
}

double side_sum(const json& j, const char* key) {
  if (!j.contains(key) || !j[key].is_object()) return kNaN;
  return j[key].value("L", kNaN) + j[key].value("R", kNaN);
}

double path_figure(const json& j, const char* key) {
  return j.contains("path") && j["path"].is_object() ? j["path"].value(key, kNaN) : kNaN;
}

json row_of(const Run& r, double first_energy) {
  const json& j = r.summary.data();
  const double e = r.aborted() ? kNaN : r.summary.energy_J();
  return {{"variant", r.label},
          {"id", r.id},
          {"status", r.status()},
          {"energy_J", num(e)},
          {"saving_pct", num(100.0 * (first_energy - e) / first_energy)},
          {"mileage_m_per_J", num(r.mileage())},
          {"distance_m", num(r.aborted() ? kNaN : r.summary.distance_m())},
          {"cross_track_max_m", num(path_figure(j, "cross_track_max_m"))},
          {"final_position_error_m", num(path_figure(j, "final_position_error_m"))},
          {"mean_active_agents", num(j.value("mean_active_agents", kNaN))},
          {"discharge_mAh", num(side_sum(j, "battery_discharge_mAh"))},
          {"trace_sha256", j.value("trace_sha256", "")}};
}

/// compare.png: four panels on common time axes, one curve per variant.
void plot(Experiment& e, const std::vector<std::pair<std::string, std::string>>& files) {
  // Each variant its own dash and width, so that identical curves stay visible on each other.
  const auto panel = [&](const std::string& title, const std::string& ylabel, const std::string& col) {
    std::vector<report::Curve> curves;
    for (std::size_t i = 0; i < files.size(); ++i)
      curves.push_back(
          {"series/" + files[i].first + ".csv", "t_s", col,
           "lines lw " + std::to_string(files.size() + 1 - i) + " dt " + std::to_string(i % 5 + 1),
           files[i].second, ""});
    return "set title '" + title + "'\nset ylabel '" + ylabel + "'\n" + report::plot_command(curves);
  };
  e.plot("compare",
         "set multiplot layout 2,2\nset key inside bottom right\nset xlabel 'time (s)'\n" +
             panel("Speed", "speed (m/s)", "v_x_mps") +
             panel("Active agents (L + R)", "active agents", "n_active") +
             panel("Energy drawn", "energy (kJ)", "energy_kJ") +
             panel("Battery voltage", "V_B (V, mean of L and R)", "battery_V") + "unset multiplot\n",
         report::PlotFrame{"1400,900", ",10"});
}

}  // namespace

std::vector<CompareVariant> compare_variants(const CompareOptions& c) {
  std::vector<Sweep> sweeps;
  for (const auto& s : c.sets.empty() ? std::vector<std::string>{"mode=ec,all"} : c.sets)
    sweeps.push_back(parse_set(s));
  std::vector<CompareVariant> out = {{"", "", config::load_scenario(c.scenario)}};
  if (!c.duration.empty()) config::set_duration(out[0].s, c.duration, "--duration");
  for (const Sweep& w : sweeps) {
    std::vector<CompareVariant> next;
    for (const auto& v : out)
      for (const auto& value : w.values) {
        CompareVariant x = v;
        if (w.field == "duration_s")
          config::set_duration(x.s, value, w.option);
        else
          config::set_field(x.s, w.field, value, w.option);
        x.id += (x.id.empty() ? "" : "_") + id_part(w.field, value);
        x.label += (x.label.empty() ? "" : " ") + w.field + "=" + value;
        next.push_back(std::move(x));
      }
    out = std::move(next);
  }
  for (auto& v : out) v.s.validate();
  return out;
}

int run_compare(const CompareOptions& c, const std::vector<CompareVariant>& variants) {
  std::filesystem::create_directories(c.o.out + "/series");
  install_stop_handler();
  ExperimentOptions o = c.o;
  o.tick_hz = variants.front().s.tick_hz;
  Experiment e(o);
  e.set_total(static_cast<int>(variants.size()));
  std::fprintf(stderr, "maptr: compare %s: %zu variants, results in %s\n", c.scenario.c_str(),
               variants.size(), c.o.out.c_str());
  records::ResultTable t;
  t.cols = records::columns::compare();
  std::vector<std::pair<std::string, std::string>> files;
  double first_energy = kNaN;
  int rc = 0;
  for (const auto& v : variants) {
    const Run r = e.run(v.id, v.label, v.s);
    if (t.rows.empty()) first_energy = r.aborted() ? kNaN : r.summary.energy_J();
    t.rows.push_back(row_of(r, first_energy));
    const std::string st = r.status();
    rc = std::max(rc, st == "ok" ? 0 : st.rfind("degraded", 0) == 0 ? 3 : 1);
    if (!r.aborted()) {
      write_series(r, c.o.out + "/series/" + v.id + ".csv", bin_for(v.s.duration_s));
      files.push_back({v.id, v.label});
    }
  }
  // Variants that ran the same trace: the values changed nothing in this scenario (e.g. EC that
  // keeps every agent on at this mass and speed), which a reader should not take for a saving of 0.
  std::string same;
  for (std::size_t i = 1; i < t.rows.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      const std::string a = t.rows[i].value("trace_sha256", ""), b = t.rows[j].value("trace_sha256", "");
      if (a.empty() || a != b) continue;
      same += "- " + t.rows[i]["variant"].get<std::string>() + " ran the same trace as " +
              t.rows[j]["variant"].get<std::string>() +
              " (equal trace_sha256): the values changed nothing here.\n";
      break;
    }
  std::ostringstream intro;
  intro << "Scenario `" << c.scenario
        << "`, one fleet per variant; saving: energy below the first variant's.";
  e.write(t, intro.str(), same, {{"scenario_file", c.scenario}});
  if (!files.empty()) plot(e, files);
  std::fprintf(stderr, "maptr: compare done: %s/compare.md, compare.csv, summary.json%s\n", c.o.out.c_str(),
               files.empty() ? "" : ", compare.png");
  for (const auto& row : t.rows)
    std::printf(
        "%-28s %-10s energy %10.1f J  saving %6.2f %%  mileage %.4f m/J  mean active %5.2f  cross-track max "
        "%.3f m\n",
        row["variant"].get<std::string>().c_str(), row["status"].get<std::string>().substr(0, 10).c_str(),
        figure(row, "energy_J"), figure(row, "saving_pct"), figure(row, "mileage_m_per_J"),
        figure(row, "mean_active_agents"), figure(row, "cross_track_max_m"));
  if (!same.empty()) std::printf("%s", same.c_str());
  return e.stopped() ? 1 : rc;
}

}  // namespace maptr::deploy
