#pragma once
// The experiments, one file each; each runs its fleets through the Experiment and returns the
// process exit code.
#include "deploy/report/gnuplot.hpp"
#include "deploy/studies/experiments/experiment.hpp"

namespace maptr::deploy {

int exp_table_pow(Experiment& e);  ///< the paper's Table: NO vs EC at six gross masses
int exp_weights(Experiment& e);    ///< EC time series at several gross masses
int exp_voltages(Experiment& e);   ///< EC time series at several supply voltages
int exp_agents(Experiment& e);     ///< energy advantage of EC against the number of agents
int exp_battery(Experiment& e);    ///< NO vs EC until the speed can no longer be held
int exp_wear(Experiment& e);       ///< Level-3 allocation: transitions, idle time, wear
int exp_failures(Experiment& e);   ///< kill 0, 1, 2, ... agents per side
int exp_turns(Experiment& e);      ///< tightest radius against speed; NO vs EC on the warehouse loop
int exp_faults(Experiment& e);     ///< every agent-fault mode, detection on and off, against the crash

/// Runs NO (every agent) and EC on the same scenario; ids and labels get -no/-ec, NO/EC.
struct RunPair {
  Run no, ec;
};
RunPair run_no_ec(Experiment& e, config::Scenario s, const std::string& id, const std::string& label);

/// One variant of an EC time-series experiment (weights, voltages).
struct SeriesVariant {
  std::string id, label;
  config::Scenario s;
  double x = 0;  ///< the swept value (gross kg or supply V)
};

/// Runs EC variants with the Level-2 oracle on, writes their table (x column `xkey`, headed
/// `xhead`), their time series and the efficiency and active-agent plots.
int ec_time_series(Experiment& e, const std::vector<SeriesVariant>& vars, const std::string& xkey,
                   const std::string& xhead, const std::string& intro, const std::string& what);

/// (E_NO - E_EC) / E_NO in percent.
double saving_pct(const RunPair& p);

/// Active agents at the end as JSON (null when unknown).
nlohmann::json active_end_json(const Run& r);

}  // namespace maptr::deploy
