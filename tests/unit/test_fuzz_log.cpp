// libFuzzer's final statistics as `maptr fuzz` reads them (deploy/studies/fuzz/fuzz_log.hpp).
#include <gtest/gtest.h>

#include "deploy/studies/fuzz/fuzz_log.hpp"

namespace {

using maptr::deploy::parse_fuzz_log;

TEST(FuzzLog, ReadsExecutionsAndRateFromTheFinalStats) {
  const std::string log =
      "INFO: Seed: 1234\n"
      "#1048576\tpulse  cov: 900 ft: 2000 corp: 120/9000b exec/s: 34952 rss: 90Mb\n"
      "Done 1048577 runs in 30 second(s)\n"
      "stat::number_of_executed_units: 1048577\n"
      "stat::average_exec_per_sec:     34952\n"
      "stat::new_units_added:          17\n"
      "stat::peak_rss_mb:              91\n";
  const auto s = parse_fuzz_log(log);
  EXPECT_EQ(s.executions, 1048577);
  EXPECT_EQ(s.exec_per_s, 34952);
}

TEST(FuzzLog, ACrashedRunWithoutStatsReadsAsUnknown) {
  const auto s = parse_fuzz_log("==12==ERROR: AddressSanitizer: heap-buffer-overflow\nSUMMARY: ...\n");
  EXPECT_EQ(s.executions, -1);
  EXPECT_EQ(s.exec_per_s, -1);
}

}  // namespace
