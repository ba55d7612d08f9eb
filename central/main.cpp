// maptr_central: the central controller (trajectory -> wheel references, count relay).
#include "central/central_node.hpp"

int main(int argc, char** argv) {
  return maptr::comm::run_named_process<maptr::central::CentralNode>(argc, argv, "central", "MAPTR central controller");
}
