#pragma once
// The plant node's thresholds (none of them is a scenario field): the barrier's last-resort
// deadline, the bounds a sample must respect, the fault gate's waits and the run status bands.
#include <chrono>
#include <vector>

#include "plant_core/speed_band.hpp"

namespace maptr::plant {

struct PlantNodeConfig {
  /// Per-tick wall-clock deadline of the barrier, s: deadline_base_s + deadline_per_agent_s * n
  /// for a fleet of n agents (the last resort only: slow is not dead).
  double deadline_base_s = 5.0;
  double deadline_per_agent_s = 0.05;
  /// Largest accepted |wheel speed reference| from central, rad/s.
  double central_ref_bound_radps = 1e4;
  /// Largest accepted |body speed| and |yaw rate| references from central, m/s and rad/s.
  double central_v_bound_mps = 1e2;
  double central_w_bound_radps = 1e2;
  /// Tolerance above the side's battery voltage an agent's applied voltage may reach, V.
  double voltage_tolerance_V = 1e-9;
  /// Final speed error above which a run that reached its reference is degraded, %.
  double degraded_band_pct = 5.0;
  /// Tracking error under which the reference counts as reached the first time, %.
  double reached_band_pct = plant_core::kSpeedBandPct;
  /// How long the speed must stay below its reference (stop_below_speed_pct) to end the run, s.
  double speed_lost_hold_s = 5.0;
  /// Wall time the plant waits for the launcher at a fault gate before going on, s.
  double gate_timeout_s = 120.0;
  /// Wall time after which tick k is sent again to a restarted member that has not answered, s.
  double resend_s = 0.2;
  /// A tick is sent again when no answer came for repair_factor x the typical barrier time
  /// (an exponential average), and at least repair_min_s: a lost sample costs that much.
  double repair_factor = 10.0;
  double repair_min_s = 0.05;
  double barrier_average_weight = 0.05;  ///< weight of the newest tick in that average
  /// Longest wait for a DDS sample inside the barrier and the fault gate, ms.
  std::chrono::milliseconds poll{50};
  /// Longest wait for a DDS sample during discovery, ms.
  std::chrono::milliseconds discovery_poll{200};
  /// Discovery without progress this long: the log names what is not matched (again every period).
  std::chrono::milliseconds discovery_report{5000};
  /// Once every endpoint is matched, longest wait for the members' hello readers before the
  /// hello goes out anyway (it only opens their ports early), ms.
  std::chrono::milliseconds hello_wait{5000};
  /// Time the last Tick is given to reach every reader before the participant goes away, ms.
  std::chrono::milliseconds linger{200};

  /// The barrier's deadline for a fleet of n agents, s.
  double deadline_s(int n_agents) const { return deadline_base_s + deadline_per_agent_s * n_agents; }
};

}  // namespace maptr::plant
