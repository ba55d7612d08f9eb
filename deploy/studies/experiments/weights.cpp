// weights: EC efficiency and active agents against time at several gross masses.
#include <sstream>

#include "deploy/studies/experiments/experiment_list.hpp"

namespace maptr::deploy {

int exp_weights(Experiment& e) {
  const bool q = e.quick();
  const std::vector<double> masses =
      q ? std::vector<double>{13.2, 33.2} : std::vector<double>{13.2, 23.2, 33.2};
  const double speed = 10.0, duration = q ? 30.0 : 600.0;
  std::vector<SeriesVariant> vars;
  for (double m : masses) {
    config::Scenario s = e.base();
    s.robot.agents = 16;
    s.robot.gross_mass_kg = m;
    s.mode = "ec";
    Experiment::straight(s, speed, duration);
    s.trace_every = trace_every_for(duration);
    vars.push_back({kg_label(m) + "kg", kg_label(m) + " kg", s, m});
  }
  std::ostringstream intro;
  intro
      << "EC, 16 agents, Type-I motors, straight line at " << speed << " m/s for " << duration
      << " s simulated, battery from full. The plots show the mean efficiency of an active agent and the "
         "number of "
         "active agents against time for each gross mass (paper: Fig. 'Level-2: different payload weights').";
  return ec_time_series(e, vars, "gross_kg", "gross kg", intro.str(),
                        "gross masses at " + records::fixed(speed, 0) + " m/s");
}

}  // namespace maptr::deploy
