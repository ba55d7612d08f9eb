#include "deploy/studies/fuzz/fuzz_log.hpp"

#include <sstream>

namespace maptr::deploy {

namespace {
/// The number after `key` on a line that starts with it, or -1.
long long stat_value(const std::string& line, const std::string& key) {
  if (line.rfind(key, 0) != 0) return -1;
  try {
    return std::stoll(line.substr(key.size()));
  } catch (...) {
    return -1;
  }
}
}  // namespace

FuzzStats parse_fuzz_log(const std::string& text) {
  FuzzStats s;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const long long e = stat_value(line, "stat::number_of_executed_units:");
    if (e >= 0) s.executions = e;
    const long long r = stat_value(line, "stat::average_exec_per_sec:");
    if (r >= 0) s.exec_per_s = r;
  }
  return s;
}

}  // namespace maptr::deploy
