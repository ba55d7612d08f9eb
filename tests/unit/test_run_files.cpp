// The JSON files of a run folder (records/run_files.hpp): their paths, the atomic writer, and a
// reader that takes anything but an object for nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "records/run_files.hpp"

namespace {

namespace fs = std::filesystem;

TEST(RunFiles, EachFileHasOnePathInTheRunFolder) {
  EXPECT_EQ(maptr::records::summary_path("runs/a"), "runs/a/summary.json");
  EXPECT_EQ(maptr::records::plant_results_path("runs/a"), "runs/a/plant.json");
  EXPECT_EQ(maptr::records::fleet_file_path("runs/a"), "runs/a/fleet.json");
}

TEST(RunFiles, WrittenWholeAndReadBackAsAnObject) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("maptr_run_files_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string path = maptr::records::summary_path(dir.string());
  const nlohmann::json j = {{"status", "ok"}, {"ticks", 12}, {"plant", {{"late_samples", 0}}}};
  maptr::records::write_json_file(path, j);
  EXPECT_EQ(maptr::records::read_json_object(path), j);
  EXPECT_FALSE(fs::exists(path + ".tmp"));  // renamed into place
  // Anything else reads as an empty object: missing, not JSON, JSON but not an object.
  EXPECT_EQ(maptr::records::read_json_object((dir / "missing.json").string()), nlohmann::json::object());
  std::ofstream(path) << "{\"status\": ";
  EXPECT_EQ(maptr::records::read_json_object(path), nlohmann::json::object());
  std::ofstream(path) << "[1, 2]";
  EXPECT_EQ(maptr::records::read_json_object(path), nlohmann::json::object());
  // A folder that cannot take the file: the writer says so.
  EXPECT_THROW(maptr::records::write_json_file((dir / "no-such-folder" / "x.json").string(), j),
               std::runtime_error);
  fs::remove_all(dir);
}

}  // namespace
