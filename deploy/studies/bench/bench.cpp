#include "deploy/studies/bench/bench.hpp"

#include <iostream>

#include "deploy/studies/bench/bench_parts.hpp"

namespace maptr::deploy {

int run_bench(const BenchOptions& o) {
  try {
    if (o.what == "scale") return bench_scale(o);
    if (o.what == "tick") return bench_tick(o);
    if (o.what == "floor") return bench_floor(o);
  } catch (const std::exception& e) {
    std::cerr << "maptr: bench " << o.what << ": " << e.what() << "\n";
    return 1;
  }
  std::cerr << "maptr: bench " << o.what << ": unknown (scale, tick, floor)\n";
  return 2;
}

}  // namespace maptr::deploy
