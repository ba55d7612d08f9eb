// voltages: EC efficiency and active agents against time at several supply voltages.
#include <sstream>

#include "deploy/studies/experiments/experiment_list.hpp"

namespace maptr::deploy {

int exp_voltages(Experiment& e) {
  const bool q = e.quick();
  const std::vector<double> volts =
      q ? std::vector<double>{12.0, 23.4} : std::vector<double>{12.0, 16.0, 20.0, 23.4};
  const double speed = 8.0, duration = q ? 30.0 : 600.0, gross = 14.4;
  std::vector<SeriesVariant> vars;
  for (double y : volts) {
    config::Scenario s = e.base();
    s.robot.agents = 16;
    s.robot.gross_mass_kg = gross;
    s.robot.battery.y = y;
    s.mode = "ec";
    Experiment::straight(s, speed, duration);
    s.trace_every = trace_every_for(duration);
    vars.push_back({kg_label(y) + "V", kg_label(y) + " V", s, y});
  }
  std::ostringstream intro;
  intro << "EC, 16 agents, Type-I motors, 10 kg payload: gross mass " << gross
        << " kg (payload + 4.4 kg of robot: 16 motors of 0.21 kg, 16 wheels of 0.05 kg and a light chassis), "
           "straight "
           "line at "
        << speed << " m/s for " << duration
        << " s simulated. The supply is set through the battery fit's y coefficient, V_B(0) = y + h ≈ y, "
           "with the "
           "discharge curve otherwise unchanged (paper: Fig. 'Level-2: different input voltages').";
  return ec_time_series(
      e, vars, "supply_V", "supply V", intro.str(),
      records::fixed(gross, 1) + " kg at " + records::fixed(speed, 0) + " m/s, several supply voltages");
}

}  // namespace maptr::deploy
