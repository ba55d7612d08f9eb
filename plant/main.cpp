// maptr_plant: the plant simulator; owns simulated time and runs the lock-step barrier.
#include "plant/plant_node.hpp"

int main(int argc, char** argv) {
  return maptr::comm::run_named_process<maptr::plant::PlantNode>(argc, argv, "plant",
                                                                 "MAPTR plant simulator");
}
