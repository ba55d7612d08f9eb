#pragma once
// Delta debugging (Zeller's ddmin) over a failing case's parts, free of fleets: given whether a
// subset of the parts still fails, the smallest subset found that fails and from which removing
// any one part makes it pass (1-minimal). `maptr shrink` uses it over a scenario's faults.
#include <functional>
#include <string>
#include <vector>

namespace maptr::deploy::shrink {

/// fails(subset): whether the case made of these parts (indices, ascending) still fails.
using Oracle = std::function<bool(const std::vector<int>&)>;
/// Told each subset tried, its size and whether it failed (for progress lines).
using StepLog = std::function<void(const std::vector<int>& subset, bool failed)>;

/// A 1-minimal failing subset of the parts 0..n-1, which fail together (not checked: the
/// caller has seen them fail). Each distinct subset is asked at most once.
std::vector<int> ddmin(int n, const Oracle& fails, const StepLog& log = {});

/// The fewest agents a fleet may have whose faults target these processes ("L3", "R1",
/// "group-L", ...): every agent named stays (per side at least its index + 1, at least 2), and
/// fleets come in fours.
int fewest_agents(const std::vector<std::string>& targets);

/// "0,3,7": a subset as a key (for a cache of outcomes).
std::string key(const std::vector<int>& subset);

}  // namespace maptr::deploy::shrink
