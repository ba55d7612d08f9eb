// records/: every file format written and read back, by column name.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "records/assignments.hpp"
#include "records/level2_log.hpp"
#include "records/summary.hpp"
#include "records/trace.hpp"

using namespace maptr::records;

namespace {

std::filesystem::path temp_dir() {
  return std::filesystem::temp_directory_path() / ("maptr_records_" + std::to_string(::getpid()));
}

std::string temp_path(const std::string& name) {
  std::filesystem::create_directories(temp_dir());
  return (temp_dir() / name).string();
}

/// Removes the folder temp_path() fills once every test has run.
class RemoveTempDir : public ::testing::Environment {
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(temp_dir(), ec);
  }
};
::testing::Environment* const kRemoveTempDir = ::testing::AddGlobalTestEnvironment(new RemoveTempDir);

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// The plant's row of trace.csv as its printf call writes it (typed: tick long long, counts int).
std::string plant_format(long long tick, const double d[21], const int n[4], double energy, double distance) {
  char buf[1024];
  std::snprintf(
      buf, sizeof(buf),
      "%lld,%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.6g,%.6g,%.9g,%.9g,"
      "%.9g,%.9g,%d,%d,%d,%d,%.9g,%.9g,0,0,0,0\n",
      tick, d[0], d[1], d[2], d[3], d[4], d[5], d[6], d[7], d[8], d[9], d[10], d[11], d[12], d[13], d[14],
      d[15], d[16], d[17], d[18], d[19], n[0], n[1], n[2], n[3], energy, distance);
  return buf;
}

TraceRow row_of(long long tick, const double d[21], const int n[4], double energy, double distance) {
  TraceRow r;
  r.tick = static_cast<double>(tick);
  double* f[] = {&r.t_s,
                 &r.x_m,
                 &r.y_m,
                 &r.theta_rad,
                 &r.v_x_mps,
                 &r.w_radps,
                 &r.phidot_L_radps,
                 &r.phidot_R_radps,
                 &r.ref_L_radps,
                 &r.ref_R_radps,
                 &r.V_L_mean_V,
                 &r.V_R_mean_V,
                 &r.I_L_A,
                 &r.I_R_A,
                 &r.eff_L,
                 &r.eff_R,
                 &r.battery_V_L,
                 &r.battery_V_R,
                 &r.discharge_L_mAh,
                 &r.discharge_R_mAh};
  for (int i = 0; i < 20; ++i) *f[i] = d[i];
  r.n_active_L = n[0];
  r.n_active_R = n[1];
  r.n_live_L = n[2];
  r.n_live_R = n[3];
  r.energy_J = energy;
  r.distance_m = distance;
  return r;
}

}  // namespace

TEST(TraceRecord, HeaderIsThePlantsHeader) {
  EXPECT_EQ(
      trace_header(),
      "tick,t_s,x_m,y_m,theta_rad,v_x_mps,w_radps,phidot_L_radps,phidot_R_radps,ref_L_radps,ref_R_radps,"
      "V_L_mean_V,V_R_mean_V,I_L_A,I_R_A,eff_L,eff_R,battery_V_L,battery_V_R,discharge_L_mAh,"
      "discharge_R_mAh,n_active_L,n_active_R,n_live_L,n_live_R,energy_J,distance_m,ref_x_m,ref_y_m,ref_theta_rad,"
      "cross_track_m\n");
}

TEST(TraceRecord, RowsAreByteIdenticalToThePlantsFormat) {
  const double a[21] = {0.01,
                        12.345678912345,
                        -0.000123456789,
                        1e-12,
                        9.87654321,
                        -3.3,
                        285.714285714,
                        285.7,
                        285.714,
                        0,
                        23.123456789,
                        0,
                        1.5,
                        0,
                        0.7426123456,
                        0.0,
                        23.39999999,
                        23.4,
                        1234.56789012,
                        0.000001,
                        0};
  const int n[4] = {3, 0, 8, 7};
  const double b[21] = {1234.5, 1e6, 2e-7, -1.0,     10.0, 0,    1,    2,      3,         4, 5,
                        6,      7,   8,    0.999999, 1.0,  17.2, 17.3, 6395.0, 6394.9999, 0};
  const int m[4] = {16, 16, 16, 16};
  EXPECT_EQ(format_trace_row(row_of(1, a, n, 123456.789012, 0.1)), plant_format(1, a, n, 123456.789012, 0.1));
  EXPECT_EQ(format_trace_row(row_of(123456789, b, m, 0, 36000.5)), plant_format(123456789, b, m, 0, 36000.5));
}

TEST(TraceRecord, WrittenFileReadsBackByName) {
  const std::string path = temp_path("trace.csv");
  const double a[21] = {0.5,   1, 2, 3,    10.25, 0.1, 1,  1,  2,  2, 12.5,
                        12.25, 3, 4, 0.75, 0.5,   23,  22, 10, 11, 0};
  const int n[4] = {3, 4, 8, 8};
  {
    TraceWriter w(path);
    w.write(row_of(0, a, n, 5.5, 1.25));
    w.write(row_of(50, a, n, 6.5, 2.25));
  }
  EXPECT_EQ(file_text(path),
            trace_header() + plant_format(0, a, n, 5.5, 1.25) + plant_format(50, a, n, 6.5, 2.25));
  const auto rows = read_trace(path);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].tick, 50);
  EXPECT_DOUBLE_EQ(rows[0].v_x_mps, 10.25);
  EXPECT_DOUBLE_EQ(rows[0].eff_L, 0.75);
  EXPECT_EQ(rows[0].n_active_R, 4);
  EXPECT_DOUBLE_EQ(rows[1].energy_J, 6.5);
  EXPECT_DOUBLE_EQ(rows[0].ref_speed_mps(0.1), 0.2);
}

TEST(TraceRecord, ColumnsAreFoundByNameInAnyOrder) {
  std::string text = trace_header();
  // Swap the first two columns of the header and of the row: the reader follows the names.
  text = "t_s,tick" + text.substr(std::string("tick,t_s").size());
  std::string row = "2.5,250";
  for (std::size_t i = 2; i < trace_columns().size(); ++i) row += ",0";
  const auto rows = parse_trace(text + row + "\n");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].tick, 250);
  EXPECT_DOUBLE_EQ(rows[0].t_s, 2.5);
}

TEST(TraceRecord, MissingColumnIsNamed) {
  std::string head = trace_header();
  head.replace(head.find("eff_R"), 5, "eff_X");
  try {
    parse_trace(head);
    FAIL() << "a trace without eff_R was read";
  } catch (const RecordError& e) {
    EXPECT_NE(std::string(e.what()).find("'eff_R'"), std::string::npos) << e.what();
  }
}

TEST(TraceRecord, MalformedNumberNamesLineAndColumn) {
  std::string row = "0,0.0,abc";
  for (std::size_t i = 3; i < trace_columns().size(); ++i) row += ",0";
  try {
    parse_trace(trace_header() + row + "\n");
    FAIL() << "a malformed number was read";
  } catch (const RecordError& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("line 2"), std::string::npos) << w;
    EXPECT_NE(w.find("'x_m'"), std::string::npos) << w;
    EXPECT_NE(w.find("'abc'"), std::string::npos) << w;
  }
}

TEST(TraceRecord, AnInterruptedLastLineIsNotRead) {
  std::string row = "7,0.07";
  for (std::size_t i = 2; i < trace_columns().size(); ++i) row += ",1";
  const auto rows = parse_trace(trace_header() + row + "\n" + "8,0.08,1.2");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].tick, 7);
}

TEST(Level2Log, LinesAreWhatAStreamWrites) {
  Level2Record r{12.5, 8, 3, 1, 2.71828182, 3, -1, 4, 0.123456789};
  std::ostringstream expected;  // the group controller's stream output of the same values
  expected << 12.5 << ',' << 8 << ',' << 3 << ',' << 1 << ',' << 2.71828182 << ',' << 3 << ',' << -1 << ','
           << 4 << ',' << 0.123456789 << '\n';
  EXPECT_EQ(format_level2_record(r), expected.str());
}

TEST(Level2Log, AppendsAndReadsBack) {
  const std::string path = temp_path("level2-L.csv");
  std::filesystem::remove(path);
  { Level2LogWriter(path).write({1, 8, 3, 1, 3.4, 3, 3, 3, 2.5}); }
  { Level2LogWriter(path).write({2, 7, 3, 2, 7.9, 7, -1, 7, 4.25}); }  // a restarted controller
  const std::string text = file_text(path);
  EXPECT_EQ(text.find("t_s,"), 0u);
  EXPECT_EQ(text.find("t_s,", 1), std::string::npos) << "the header is written once";
  const auto rows = read_level2_log(path);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_DOUBLE_EQ(rows[0].solve_ms, 2.5);
  EXPECT_EQ(rows[1].status, 2);
  EXPECT_EQ(rows[1].oracle_n_active, -1);
  EXPECT_EQ(level2_log_path("/run", 1), "/run/level2-R.csv");
}

TEST(Level2Log, MissingColumnAndMalformedNumber) {
  EXPECT_THROW(parse_level2_log("t_s,n_live\n1,2\n"), RecordError);
  EXPECT_THROW(parse_level2_log("t_s,n_live,n_other,status,relaxed,ipopt_n_active,oracle_n_active,n_target,"
                                "solve_ms\n1,2,3,x,5,6,7,8,9\n"),
               RecordError);
}

TEST(Assignments, RoundTrip) {
  const std::string path = temp_path("assignments.csv");
  {
    AssignmentsWriter w(path);
    w.write({0.01, 'L', "11110000"});
    w.write({0.01, 'R', "11110000"});
    w.write({5.5, 'L', "00001111"});
  }
  EXPECT_EQ(file_text(path),
            "t_s,side,driving\n0.010000,L,11110000\n0.010000,R,11110000\n5.500000,L,00001111\n");
  const auto rows = read_assignments(path);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1].side, 'R');
  EXPECT_DOUBLE_EQ(rows[2].t_s, 5.5);
  EXPECT_EQ(rows[2].driving, "00001111");
}

TEST(Assignments, MissingColumnMalformedTimeAndBadSide) {
  EXPECT_THROW(parse_assignments("t_s,driving\n0.1,1111\n"), RecordError);
  EXPECT_THROW(parse_assignments("t_s,side,driving\nnope,L,1111\n"), RecordError);
  EXPECT_THROW(parse_assignments("t_s,side,driving\n0.1,X,1111\n"), RecordError);
}

TEST(SummaryRecord, TypedAccessors) {
  const nlohmann::json j = {
      {"status", "ok"},
      {"energy_J", 1500.0},
      {"active_agents", {{"L", 3}, {"R", 4}}},
      {"level2",
       {{"L", {{"decisions", 5}, {"oracle_checked", 4}, {"oracle_differs", 1}, {"solve_ms_median", 2.0}}}}},
      {"failures", {{{"detected_s", 15.01}, {"recovered_s", nullptr}, {"detect_wall_ms", 3.5}}}},
      {"plant",
       {{"battery_V", {{"L", 22.0}, {"R", 21.0}}},
        {"agent_active_s", {{"L", {1.0, 2.0}}}},
        {"tick_timing_us", {{"tick", {{"median", 1800.0}, {"p90", 2000.0}, {"p99", 2500.0}}}}}}}};
  const Summary s(j);
  EXPECT_EQ(s.status(), "ok");
  EXPECT_DOUBLE_EQ(s.energy_J(), 1500.0);
  EXPECT_TRUE(std::isnan(s.distance_m()));
  EXPECT_EQ(s.active_agents("R"), 4);
  ASSERT_EQ(s.level2().size(), 1u);
  EXPECT_EQ(s.level2()[0].oracle_differs, 1);
  ASSERT_EQ(s.failures().size(), 1u);
  EXPECT_DOUBLE_EQ(s.failures()[0].detected_s, 15.01);
  EXPECT_TRUE(std::isnan(s.failures()[0].recovered_s));
  EXPECT_DOUBLE_EQ(s.plant_side(summary_key::kBatteryV, "R"), 21.0);
  EXPECT_EQ(s.agent_active_s("L").size(), 2u);
  EXPECT_TRUE(s.agent_active_s("R").empty());
  EXPECT_TRUE(s.tick_timing("tick").present);
  EXPECT_DOUBLE_EQ(s.tick_timing("tick").p99, 2500.0);
  EXPECT_FALSE(s.tick_timing("barrier").present);
}

TEST(SummaryRecord, MissingOrBrokenFileIsEmpty) {
  EXPECT_FALSE(Summary::read("/nonexistent/summary.json").has_status());
  const std::string path = temp_path("summary.json");
  std::ofstream(path) << "{not json";
  EXPECT_FALSE(Summary::read(path).has_status());
  EXPECT_EQ(Summary::read(path).active_agents("L"), -1);
}
