// `maptr experiment NAME`: the paper's experiments on the real multi-process fleet. Every
// scenario variant is one fleet launch (run to its end); the experiment then reads what the
// fleet wrote and writes its tables and plots (see experiment.hpp). A variant whose folder
// already holds a finished run of the identical scenario is not run again (an interrupted
// experiment resumes); delete runs/<variant>/ to force it.
#include "deploy/studies/experiments/experiments.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include "deploy/fleet/isolated_launch.hpp"
#include "deploy/studies/experiments/experiment_list.hpp"

namespace maptr::deploy {

namespace {
/// The tick rates of default_tick_hz(): the scenarios' own rate for failures and faults
/// (detection times are counted in ticks) and turns (the loop's wheel gains are tuned at it).
constexpr double kScenarioTickHz = 100.0, kMissionTickHz = 20.0;

using Body = int (*)(Experiment&);
const std::map<std::string, Body>& bodies() {
  static const std::map<std::string, Body> m = {
      {"table-pow", exp_table_pow}, {"weights", exp_weights}, {"voltages", exp_voltages},
      {"agents", exp_agents},       {"battery", exp_battery}, {"wear", exp_wear},
      {"failures", exp_failures},   {"turns", exp_turns},     {"faults", exp_faults}};
  return m;
}

void print_done(const ExperimentOptions& o, const Experiment& e) {
  std::fprintf(stderr, "maptr: experiment %s done: %s/%s.md, %s.csv, summary.json", o.name.c_str(),
               o.out.c_str(), o.name.c_str(), o.name.c_str());
  for (const auto& p : e.plots()) std::fprintf(stderr, ", %s", p.c_str());
  std::fprintf(stderr, "\n");
}
}  // namespace

RunPair run_no_ec(Experiment& e, config::Scenario s, const std::string& id, const std::string& label) {
  RunPair p;
  s.mode = "all";
  p.no = e.run(id + "-no", label + " NO", s);
  s.mode = "ec";
  p.ec = e.run(id + "-ec", label + " EC", s);
  return p;
}

double saving_pct(const RunPair& p) {
  return 100.0 * (p.no.energy_kJ() - p.ec.energy_kJ()) / p.no.energy_kJ();
}

nlohmann::json active_end_json(const Run& r) {
  return r.active_end() >= 0 ? nlohmann::json(r.active_end()) : nlohmann::json(nullptr);
}

double default_tick_hz(const std::string& name) {
  return name == "failures" || name == "turns" || name == "faults" ? kScenarioTickHz : kMissionTickHz;
}

std::vector<std::string> experiment_names() {
  return {"table-pow", "weights", "voltages", "agents", "battery", "wear", "failures", "turns", "faults"};
}

int run_experiment(const ExperimentOptions& o) {
  const auto it = bodies().find(o.name);
  if (it == bodies().end()) {
    std::string list;
    for (const auto& n : experiment_names()) list += (list.empty() ? "" : ", ") + n;
    std::cerr << "maptr: unknown experiment '" << o.name << "'; known: " << list << "\n";
    return 2;
  }
  try {
    std::filesystem::create_directories(o.out);
    install_stop_handler();
    Experiment e(o);
    std::fprintf(stderr, "maptr: experiment %s%s, results in %s\n", o.name.c_str(), o.quick ? " (quick)" : "",
                 o.out.c_str());
    const int rc = it->second(e);
    print_done(o, e);
    return e.stopped() ? 1 : rc;
  } catch (const std::exception& ex) {
    std::cerr << "maptr: experiment " << o.name << ": " << ex.what() << "\n";
    return 1;
  }
}

}  // namespace maptr::deploy
