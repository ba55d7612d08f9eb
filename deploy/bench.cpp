#include "deploy/bench.hpp"

#include <iostream>

namespace maptr::deploy {

int run_bench(const BenchOptions& o) {
  std::cerr << "maptr: bench " << o.what << " is not implemented yet\n";
  return 1;
}

}  // namespace maptr::deploy
