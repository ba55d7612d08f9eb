#pragma once
// The three benches of `maptr bench`, each on its own fleets (launched in child processes).
#include "config/scenario.hpp"
#include "deploy/studies/bench/bench.hpp"

namespace maptr::deploy {

/// `maptr bench scale`: one fleet per size in o.agents; scale.csv, scale.md, scale.png.
int bench_scale(const BenchOptions& o);

/// `maptr bench tick`: one fleet; the plant's tick timing as tick.md and tick.json.
int bench_tick(const BenchOptions& o);

/// `maptr bench floor`: the IPC floor of each size with each working set per process;
/// floor.csv, floor.md, floor.png (no fleet).
int bench_floor(const BenchOptions& o);

}  // namespace maptr::deploy
