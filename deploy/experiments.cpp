#include "deploy/experiments.hpp"

#include <iostream>

namespace maptr::deploy {

std::vector<std::string> experiment_names() {
  return {"table-pow", "weights", "voltages", "agents", "battery", "wear", "failures"};
}

int run_experiment(const ExperimentOptions& o) {
  std::cerr << "maptr: experiment " << o.name << " is not implemented yet\n";
  return 1;
}

}  // namespace maptr::deploy
