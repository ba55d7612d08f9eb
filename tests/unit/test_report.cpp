// records/result_table (the result tables of experiments and benches) and deploy/report (their plots).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "deploy/report/gnuplot.hpp"
#include "records/csv.hpp"
#include "records/result_table.hpp"

using namespace maptr::deploy::report;
using maptr::records::read_result_table;
using maptr::records::ResultTable;
using maptr::records::ResultTableWriter;
using maptr::records::write_text_file;
using nlohmann::json;

namespace {
ResultTable sample() {
  ResultTable t;
  t.cols = {{"gross_kg", "gross kg", 1},
            {"E_kJ", "E kJ", 2},
            {"active", "active", 0},
            {"hidden", "hidden", 3, false},
            {"status", "status", -1}};
  t.rows = {
      {{"gross_kg", 13.2}, {"E_kJ", 92.333}, {"active", 3}, {"hidden", 0.5}, {"status", "ok"}},
      {{"gross_kg", 38.2}, {"E_kJ", nullptr}, {"active", 12}, {"status", "degraded: L3 died, restarted"}}};
  return t;
}
}  // namespace

TEST(ReportTable, CsvText) {
  EXPECT_EQ(sample().csv(),
            "gross_kg,E_kJ,active,hidden,status\n"
            "13.2,92.33,3,0.500,ok\n"
            "38.2,,12,,\"degraded: L3 died, restarted\"\n");
}

TEST(ReportTable, MarkdownText) {
  EXPECT_EQ(sample().md(),
            "| gross kg | E kJ | active | status |\n"
            "|---|---|---|---|\n"
            "| 13.2 | 92.33 | 3 | ok |\n"
            "| 38.2 | – | 12 | degraded: L3 died, restarted |\n");
}

TEST(ReportTable, WrittenThenReadBack) {
  const auto path =
      (std::filesystem::temp_directory_path() / ("maptr_report_" + std::to_string(::getpid()) + ".csv"))
          .string();
  const ResultTable t = sample();
  t.write_csv(path);
  const auto rows = read_result_table(path, t.cols);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_DOUBLE_EQ(rows[0]["E_kJ"].get<double>(), 92.33);  // at the column's decimals
  EXPECT_EQ(rows[0]["active"].get<double>(), 3);
  EXPECT_TRUE(rows[1]["E_kJ"].is_null());
  EXPECT_EQ(rows[1]["status"], "degraded: L3 died, restarted");
  auto cols = t.cols;
  cols.push_back({"missing", "m", 1});
  EXPECT_THROW(read_result_table(path, cols), maptr::records::RecordError);
  std::filesystem::remove(path);
}

TEST(ReportTable, AWriterLeavesEveryRowAppendedSoFar) {
  const auto path =
      (std::filesystem::temp_directory_path() / ("maptr_rows_" + std::to_string(::getpid()) + ".csv"))
          .string();
  const ResultTable t = sample();
  ResultTableWriter w(path, t.cols);
  w.append(t.rows[0]);
  {  // read while the writer is still open: the header and the first row are on disk
    std::ifstream in(path);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    EXPECT_EQ(text, "gross_kg,E_kJ,active,hidden,status\n13.2,92.33,3,0.500,ok\n");
  }
  w.append(t.rows[1]);
  EXPECT_EQ(read_result_table(path, t.cols).size(), 2u);
  std::filesystem::remove(path);
}

TEST(ReportTable, CsvOnlyAndMarkdownOnlyColumns) {
  ResultTable t;
  t.cols = {{"pss_kB", "", 0, false, true}, {"pss_MB", "PSS MB", 1, true, false}};
  t.rows = {{{"pss_kB", 10240.0}, {"pss_MB", 10.0}}};
  EXPECT_EQ(t.csv(), "pss_kB\n10240\n");
  EXPECT_EQ(t.md(), "| PSS MB |\n|---|\n| 10.0 |\n");
}

TEST(ReportGnuplot, ScriptNamesTheColumns) {
  const std::string body = plot_command({{"t.csv", "gross_kg", "E_NO_kJ", "linespoints", "NO", ""},
                                         {"", "gross_kg", "E_EC_kJ", "points", "EC", "x1y2"}});
  EXPECT_EQ(body,
            "plot 't.csv' using \"gross_kg\":\"E_NO_kJ\" with linespoints title 'NO', \\\n"
            "     '' using \"gross_kg\":\"E_EC_kJ\" with points axes x1y2 title 'EC'\n");
  const std::string gp = plot_script("energy", "made by a test", PlotFrame{"900,600", ",11"}, body);
  EXPECT_EQ(gp.find("# made by a test\nset terminal pngcairo size 900,600 font ',11' noenhanced\n"
                    "set output 'energy.png'\nset datafile separator ','\n"),
            0u);
  EXPECT_NE(gp.find(body), std::string::npos);
}

TEST(ReportGnuplot, DrawsThePngFromTheCsv) {
  const auto dir = std::filesystem::temp_directory_path() / ("maptr_plot_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  ResultTable t = sample();
  t.write_csv((dir / "t.csv").string());
  if (std::system("gnuplot --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "no gnuplot";
  ASSERT_TRUE(draw_plot(dir.string(), "t", "test", PlotFrame{},
                        "set datafile columnheaders\n" +
                            plot_command({{"t.csv", "gross_kg", "active", "linespoints", "active", ""}})));
  EXPECT_TRUE(std::filesystem::exists(dir / "t.png"));
  EXPECT_FALSE(std::filesystem::exists(dir / "t.gnuplot.log"));
  std::filesystem::remove_all(dir);
}
