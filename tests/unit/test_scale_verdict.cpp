// bench scale's answer per size (status and thresholds) and the JUnit XML it writes.
#include <gtest/gtest.h>

#include "deploy/studies/bench/scale_verdict.hpp"
#include "records/junit.hpp"

namespace {

using maptr::deploy::scale_headline;
using maptr::deploy::scale_misses;
using maptr::deploy::ScaleThresholds;

nlohmann::json row(const std::string& status, double rtf, double x_floor) {
  return {{"agents", 16},         {"mode", "ec"},       {"hosts", 1},           {"status", status.substr(0, status.find(':'))},
          {"status_full", status}, {"real_time_factor", rtf}, {"x_floor", x_floor}, {"tick_median_us", 1200.0},
          {"discovery_s", 1.5}};
}

TEST(ScaleVerdict, ASizePassesOnlyWhenOkAndWithinEveryThresholdGiven) {
  EXPECT_TRUE(scale_misses(row("ok", 90, 2.5), {}).empty());
  EXPECT_TRUE(scale_misses(row("ok", 90, 2.5), ScaleThresholds{50, 3}).empty());
  const auto slow = scale_misses(row("ok", 40, 2.5), ScaleThresholds{50, -1});
  ASSERT_EQ(slow.size(), 1u);
  EXPECT_EQ(slow[0], "RTF 40.0 < --min-rtf 50");
  const auto both = scale_misses(row("degraded: stalled", 40, 6), ScaleThresholds{50, 3});
  ASSERT_EQ(both.size(), 3u);
  EXPECT_EQ(both[0], "status degraded: stalled");
  EXPECT_EQ(both[2], "tick / floor 6.0 > --max-floor-ratio 3");
  // A floor that was not measured (0) cannot meet a floor bound.
  EXPECT_EQ(scale_misses(row("ok", 90, 0), ScaleThresholds{-1, 3}).size(), 1u);
  EXPECT_EQ(scale_headline(row("ok", 90, 2.5), {}),
            "N=16 ec, 1 host: ok, RTF 90.0, tick 1.20 ms = 2.5 x floor, discovery 1.50 s: PASS");
  EXPECT_NE(scale_headline(row("ok", 40, 2.5), slow).find(": MISS (RTF 40.0 < --min-rtf 50)"), std::string::npos);
}

TEST(Junit, CasesAndFailuresAreCountedAndTextIsEscaped) {
  const std::string x = maptr::records::junit_xml(
      "suite <1>", {{"N16-ec", "maptr.bench.scale", 1.5, ""}, {"N32-all", "maptr.bench.scale", 2.0, "RTF 3 < 5 & \"x\""}});
  EXPECT_NE(x.find("<testsuite name=\"suite &lt;1&gt;\" tests=\"2\" failures=\"1\" errors=\"0\" skipped=\"0\" time=\"3.500\">"),
            std::string::npos)
      << x;
  EXPECT_NE(x.find("<testcase name=\"N16-ec\" classname=\"maptr.bench.scale\" time=\"1.500\"/>"), std::string::npos) << x;
  EXPECT_NE(x.find("<failure message=\"RTF 3 &lt; 5 &amp; &quot;x&quot;\""), std::string::npos) << x;
}

}  // namespace
