#pragma once
// Each core's configuration built from the scenario, beside the field table: the one place where
// a scenario field reaches the core that uses it. The nodes hand these to their cores.
#include "config/scenario.hpp"
#include "control/central_core.hpp"
#include "control/group_core.hpp"
#include "control/level1/agent_core.hpp"
#include "plant_core/plant_core.hpp"

namespace maptr::config {

control::AgentConfig agent_config(const Scenario& s);
control::GroupConfig group_config(const Scenario& s);
control::CentralConfig central_config(const Scenario& s);
/// The plant core's configuration; `speed_lost_hold_s` and `reached_band_pct` are the plant
/// node's own settings (plant/plant_config.hpp), not the scenario's.
plant_core::PlantCoreConfig plant_core_config(const Scenario& s, double speed_lost_hold_s,
                                              double reached_band_pct);

}  // namespace maptr::config
