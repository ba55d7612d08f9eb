// deploy/report/run_plot: the events marked on run.png and the script that draws them.
#include <gtest/gtest.h>

#include "deploy/report/run_plot.hpp"

using maptr::deploy::report::path_notes;
using maptr::deploy::report::place_events;
using maptr::deploy::report::run_events;
using maptr::deploy::report::run_plot_body;
using maptr::deploy::report::RunPlotSpec;
using maptr::deploy::report::scan_trace;

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

TEST(RunPlot, EveryEventIsALineAcrossThePanelsAndNamedInTheEventsPanel) {
  RunPlotSpec spec;
  spec.title = "t";
  spec.has_path = false;
  spec.t0 = 0;
  spec.t1 = 10;
  const std::string body = run_plot_body(spec, run_events(kSummary));
  auto count = [&](const std::string& what) {
    std::size_t n = 0;
    for (auto p = body.find(what); p != std::string::npos; p = body.find(what, p + 1)) ++n;
    return n;
  };
  // A line before each panel (the events panel and the four time panels), numbered and named
  // once, in the events panel.
  EXPECT_EQ(count("set arrow from 5.02,"), 5u);
  EXPECT_EQ(count("unset arrow"), 5u);
  EXPECT_EQ(count("L3 died'"), 1u);
  EXPECT_EQ(count("set label '2 L3 died' at 5.02,"), 1u);
  EXPECT_EQ(count("plot 'trace.csv'"), 4u);  // a trace without the path: the four time panels
  // The reference speed: the mean wheel reference times the wheel radius.
  EXPECT_NE(body.find("(column(\"ref_L_radps\")+column(\"ref_R_radps\"))/2*0.035"), std::string::npos);
  EXPECT_NE(body.find("set yrange [0:9.2]"), std::string::npos);  // 8 per side, 15 % headroom
}

namespace {
constexpr const char* kOldTrace = "tick,t_s,x_m,y_m,theta_rad\n0,0,0,0,0\n1,1,1,0,0\n2,2,2,0.5,0\n";
constexpr const char* kNewTrace =
    "tick,t_s,x_m,y_m,theta_rad,ref_x_m,ref_y_m,ref_theta_rad,cross_track_m\n0,0,0,0,0,0,0,0,0\n";
}  // namespace

TEST(RunPlot, ATraceWithoutTheReferencePoseHasNoPathPanelsAndSaysSo) {
  EXPECT_FALSE(scan_trace(kOldTrace).has_path);
  EXPECT_TRUE(scan_trace(kNewTrace).has_path);
  const auto notes = path_notes(kSummary, false);
  ASSERT_FALSE(notes.empty());
  EXPECT_NE(notes[0].find("No path panels"), std::string::npos);
}

TEST(RunPlot, EventsArePlacedWhereTheRobotWasAtTheirTime) {
  auto e = run_events(kSummary);  // 5.0, 5.02, 9.0, 9.01 s
  e.insert(e.begin(), maptr::deploy::report::RunEvent{-1.0, "early", true});
  place_events(e, scan_trace(kOldTrace));
  ASSERT_TRUE(e[0].placed);
  EXPECT_DOUBLE_EQ(e[0].x_m, 0.0);  // before the first row: the first row
  EXPECT_DOUBLE_EQ(e[1].x_m, 2.0);  // after the last row: the last row
  EXPECT_DOUBLE_EQ(e[1].y_m, 0.5);
}

TEST(RunPlot, WithThePathSevenTimePanelsAndThePathAtEqualScales) {
  RunPlotSpec spec;
  spec.title = "t";
  spec.track_m = 0.2;
  spec.notes = path_notes({{"path", {{"cross_track_max_m", 0.1234}, {"cross_track_max_t_s", 30.0}}}}, true);
  auto e = run_events(kSummary);
  place_events(e, scan_trace(kNewTrace));
  const std::string body = run_plot_body(spec, e);
  auto count = [&](const std::string& what) {
    std::size_t n = 0;
    for (auto p = body.find(what); p != std::string::npos; p = body.find(what, p + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("plot 'trace.csv'"), 8u);
  EXPECT_NE(body.find("set size ratio -1"), std::string::npos);
  EXPECT_NE(body.find("\"ref_x_m\":\"ref_y_m\""), std::string::npos);
  // The reference yaw rate: r (phidot_ref_R - phidot_ref_L) / a.
  EXPECT_NE(body.find("((column(\"ref_R_radps\")-column(\"ref_L_radps\"))*0.035/0.2)"), std::string::npos);
  EXPECT_NE(body.find("set label '2' at 0,0 point"), std::string::npos);  // numbered as in the events panel
  EXPECT_NE(body.find("cross-track max 0.123 m at 30.0 s"), std::string::npos);
}

TEST(RunPlot, EventLabelsTakeRowsWithoutCoveringOneAnother) {
  using maptr::deploy::report::label_rows;
  using maptr::deploy::report::RunEvent;
  // 100 characters across 100 s: one character a second; "N label" takes size + digits + 3.
  const std::vector<RunEvent> ev = {{10, "kill L3", true},  {12, "L3 died", false}, {30, "kill L4", true},
                                    {31, "L4 died", false}, {60, "pause central", true}};
  const auto rows = label_rows(ev, 0, 100, 100, 7);
  EXPECT_EQ(rows, (std::vector<int>{0, 1, 0, 1, 0}));
  // With one row only, the later labels go to the row that ends first (they overlap: nothing else is left).
  EXPECT_EQ(label_rows(ev, 0, 100, 100, 1), (std::vector<int>{0, 0, 0, 0, 0}));
  // Labels far apart share the top row.
  EXPECT_EQ(label_rows({{0, "a", true}, {50, "b", true}}, 0, 100, 100, 7), (std::vector<int>{0, 0}));
}

TEST(RunPlot, TheBodyHasAnEventsPanelAndAWearPanelWhenItHasTheirData) {
  using namespace maptr::deploy::report;
  RunPlotSpec spec;
  spec.title = "t";
  spec.t0 = 0;
  spec.t1 = 20;
  spec.wear_L = {1.5, 2.5};
  spec.wear_R = {3.0, 0.0};
  const std::string b = run_plot_body(spec, {{5, "kill L3", true}});
  EXPECT_NE(b.find("set ylabel 'events'"), std::string::npos);
  EXPECT_NE(b.find("set label '1 kill L3' at 5,"), std::string::npos) << b;
  EXPECT_NE(b.find("set xrange [0:20]"), std::string::npos);
  EXPECT_NE(b.find("$wear << EOD\n0,L0,1.5,0\n1,L1,2.5,0\n2,R0,3,1\n3,R1,0,1\nEOD"), std::string::npos) << b;
  spec.wear_L.clear();
  spec.wear_R.clear();
  const std::string none = run_plot_body(spec, {});
  EXPECT_EQ(none.find("events'"), std::string::npos);
  EXPECT_EQ(none.find("$wear"), std::string::npos);
}
