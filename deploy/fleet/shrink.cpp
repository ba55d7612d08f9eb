#include "deploy/fleet/shrink.hpp"

#include <algorithm>
#include <map>

#include "config/scenario.hpp"

namespace maptr::deploy::shrink {

std::string key(const std::vector<int>& subset) {
  std::string k;
  for (const int i : subset) k += (k.empty() ? "" : ",") + std::to_string(i);
  return k;
}

namespace {
/// `parts` cut into n chunks of (nearly) equal size, in order.
std::vector<std::vector<int>> chunks(const std::vector<int>& parts, int n) {
  std::vector<std::vector<int>> out;
  const int size = static_cast<int>(parts.size());
  int start = 0;
  for (int i = 0; i < n; ++i) {
    const int end = start + (size - start) / (n - i);
    out.emplace_back(parts.begin() + start, parts.begin() + end);
    start = end;
  }
  return out;
}

std::vector<int> without(const std::vector<int>& parts, const std::vector<int>& removed) {
  std::vector<int> out;
  for (const int p : parts)
    if (!std::binary_search(removed.begin(), removed.end(), p)) out.push_back(p);
  return out;
}
}  // namespace

std::vector<int> ddmin(int n_parts, const Oracle& fails, const StepLog& log) {
  std::vector<int> parts(static_cast<std::size_t>(std::max(0, n_parts)));
  for (int i = 0; i < n_parts; ++i) parts[static_cast<std::size_t>(i)] = i;
  std::map<std::string, bool> seen;
  auto ask = [&](const std::vector<int>& s) {
    const std::string k = key(s);
    if (const auto it = seen.find(k); it != seen.end()) return it->second;
    const bool f = fails(s);
    seen[k] = f;
    if (log) log(s, f);
    return f;
  };
  int n = 2;
  while (parts.size() >= 2) {
    n = std::min(n, static_cast<int>(parts.size()));
    const auto cs = chunks(parts, n);
    bool reduced = false;
    for (const auto& c : cs)  // a chunk alone fails: keep only it
      if (ask(c)) {
        parts = c;
        n = 2;
        reduced = true;
        break;
      }
    if (!reduced)
      for (const auto& c : cs) {  // all but a chunk fails: drop that chunk
        const auto rest = without(parts, c);
        if (n > 2 && ask(rest)) {
          parts = rest;
          n = std::max(n - 1, 2);
          reduced = true;
          break;
        }
      }
    if (reduced) continue;
    if (n >= static_cast<int>(parts.size())) break;  // single removals tried: 1-minimal
    n = std::min(2 * n, static_cast<int>(parts.size()));
  }
  // One part left: it fails on its own (it was asked) unless the case needs none; the empty
  // set is asked so that a case that fails without any part says so.
  if (parts.size() == 1 && ask({})) parts.clear();
  return parts;
}

int fewest_agents(const std::vector<std::string>& targets) {
  int per_side = 2;
  for (const auto& t : targets) {
    int side = 0, index = 0;
    if (config::parse_agent_name(t, side, index)) per_side = std::max(per_side, index + 1);
  }
  return (per_side + 1) / 2 * 4;
}

}  // namespace maptr::deploy::shrink
