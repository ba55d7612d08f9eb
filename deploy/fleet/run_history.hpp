#pragma once
// A finished run's history as the properties read it (deploy/fleet/run_properties.hpp), loaded
// from its folder: summary.json, trace.csv, whether run.mcap is there, and the scenario's
// recording choice and path tolerance from the resolved scenario.yaml.
#include <string>

#include "deploy/fleet/run_properties.hpp"

namespace maptr::deploy::properties {

/// Throws std::runtime_error naming the folder or the file that is missing or unreadable.
History load_history(const std::string& run_dir);

/// The text of repro.yaml: the run's resolved scenario (its faults at the times they acted,
/// chaos drawn into scheduled faults) under a comment naming what broke (one line each), so that `maptr run
/// repro.yaml` runs the same fleet again.
std::string repro_yaml(const std::string& scenario_text, const std::vector<std::string>& what_broke,
                       const std::string& trace_sha256);

}  // namespace maptr::deploy::properties
