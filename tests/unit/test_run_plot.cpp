// deploy/report/run_plot: the events marked on run.png and the script that draws them.
#include <gtest/gtest.h>

#include "deploy/report/run_plot.hpp"

using maptr::deploy::report::run_events;
using maptr::deploy::report::run_plot_body;

namespace {
const nlohmann::json kSummary = {{"failures",
                                  {{{"target", "L3"}, {"action", "kill"}, {"at_s", 5.0}},
                                   {{"target", "L3"}, {"action", "restart"}, {"at_s", 9.0}},
                                   {{"target", "R1"},
                                    {"action", "kill"},
                                    {"at_s", 99.0},
                                    {"skipped", "scheduled after the end of the run"}}}},
                                 {"plant",
                                  {{"membership_events",
                                    {{{"name", "L3"}, {"event", "rejoined"}, {"t_s", 9.01}},
                                     {{"name", "L3"}, {"event", "died"}, {"t_s", 5.02}}}}}}};
}  // namespace

TEST(RunPlot, FaultsAndMembershipEventsInTimeOrderWithoutSkippedFaults) {
  const auto e = run_events(kSummary);
  ASSERT_EQ(e.size(), 4u);
  EXPECT_EQ(e[0].label, "kill L3");
  EXPECT_TRUE(e[0].fault);
  EXPECT_DOUBLE_EQ(e[1].t_s, 5.02);
  EXPECT_EQ(e[1].label, "L3 died");
  EXPECT_FALSE(e[1].fault);
  EXPECT_EQ(e[2].label, "restart L3");
  EXPECT_EQ(e[3].label, "L3 rejoined");
}

TEST(RunPlot, EveryEventIsALineAcrossThePanelsAndNamedOnTheFirst) {
  const std::string body = run_plot_body("t", 0.035, 8, run_events(kSummary));
  auto count = [&](const std::string& what) {
    std::size_t n = 0;
    for (auto p = body.find(what); p != std::string::npos; p = body.find(what, p + 1)) ++n;
    return n;
  };
  // Set with its label before the first panel, then again without it; gnuplot keeps arrows for
  // the panels that follow in a multiplot.
  EXPECT_EQ(count("set arrow from 5.02,"), 2u);
  EXPECT_EQ(count("unset arrow"), 2u);
  EXPECT_EQ(count("set label 'L3 died'"), 1u);
  EXPECT_EQ(count("plot 'trace.csv'"), 4u);
  // The reference speed: the mean wheel reference times the wheel radius.
  EXPECT_NE(body.find("(column(\"ref_L_radps\")+column(\"ref_R_radps\"))/2*0.035"), std::string::npos);
  EXPECT_NE(body.find("set yrange [0:9.2]"), std::string::npos);  // 8 per side, 15 % headroom
}
