#pragma once
// What a libFuzzer run printed with -print_final_stats=1: executions and their rate.
#include <string>

namespace maptr::deploy {

struct FuzzStats {
  long long executions = -1;  ///< stat::number_of_executed_units; -1 when absent
  long long exec_per_s = -1;  ///< stat::average_exec_per_sec; -1 when absent
};

/// Reads the last final-stats lines of a libFuzzer log.
FuzzStats parse_fuzz_log(const std::string& text);

}  // namespace maptr::deploy
