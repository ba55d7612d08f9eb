// The plant's tick records (plant/tick_records.hpp): the CSV trace and assignment rows a tick produces.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "plant/tick_records.hpp"

namespace {

using namespace maptr;

std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

TEST(PlantRunFiles, TraceAndAssignmentRows) {
  const auto dir = std::filesystem::temp_directory_path() / ("maptr_run_files_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string trace = (dir / "trace.csv").string(), assign = (dir / "assignments.csv").string();
  {
    auto files = plant::open_csv_run_files(trace, assign);
    plant_core::TickRecord rec;
    plant_core::TraceRow row;
    row.tick = 3;
    row.t_s = 0.03;
    row.x[model::kVx] = 0.25;
    row.x[model::kEnergyL] = 1.5;
    row.x[model::kEnergyR] = 2.0;
    row.ref_radps[0] = 7.0;
    row.voltage_mean_V[0] = 12.0;
    row.efficiency_mean[1] = 0.123456789;
    row.n_active[0] = 2;
    row.n_live[1] = 4;
    rec.row = row;
    rec.assignments.push_back({0.03, 1, {1, 0, 0, 1}});
    files->write(rec);
  }
  const auto t = lines(trace);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].rfind("tick,t_s,x_m,", 0), 0u);
  EXPECT_EQ(t[1], "3,0.030000,0,0,0,0.25,0,0,0,7,0,12,0,0,0,0,0.123457,0,0,0,0,2,0,0,4,3.5,0,0,0,0,0");
  EXPECT_EQ(lines(assign), (std::vector<std::string>{"t_s,side,driving", "0.030000,R,1001"}));
  std::filesystem::remove_all(dir);
}

TEST(PlantRunFiles, NoAssignmentsFileWhenNotAsked) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("maptr_run_files_b_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    auto files = plant::open_csv_run_files((dir / "trace.csv").string(), "");
    plant_core::TickRecord rec;
    rec.assignments.push_back({0.0, 0, {1}});
    files->write(rec);
  }
  EXPECT_EQ(lines((dir / "trace.csv").string()).size(), 1u);  // header only: the tick was not traced
  EXPECT_FALSE(std::filesystem::exists(dir / "assignments.csv"));
  std::filesystem::remove_all(dir);
  EXPECT_THROW(plant::open_csv_run_files("/nonexistent/dir/trace.csv", ""), std::runtime_error);
}

}  // namespace
