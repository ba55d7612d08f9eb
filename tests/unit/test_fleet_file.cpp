// fleet.json (records/fleet_file.hpp): what the launcher writes the tools read back; a process's
// host is absent unless set; a fleet not started yet is nothing, or a clear error for `maptr top`.
#include <gtest/gtest.h>

#include <fstream>

#include "records/fleet_file.hpp"
#include "records/run_files.hpp"
#include "tests/unit/unit_temp_dir.hpp"

namespace {

using maptr::records::FleetFile;

FleetFile sample() {
  FleetFile f;
  f.launcher_pid = 4242;
  f.domain = 77;
  f.discovery_server = "127.0.0.1:11888";
  f.discovery_server_pid = 4243;
  f.lease_s = 2.0;
  f.fleet_id = 987654321;
  f.config = "runs/x/scenario.yaml";
  f.run_dir = "runs/x";
  f.processes = {{"plant", 4244, false, 2, std::nullopt}, {"L0", 4250, false, 6, std::string("h1")}};
  return f;
}

TEST(FleetFile, WhatTheLauncherWritesIsReadBack) {
  const maptr::testing::UnitTempDir tmp("fleet_file");
  maptr::records::write_fleet_file(tmp.path(), sample());
  const auto f = maptr::records::read_fleet_file(tmp.path());
  ASSERT_TRUE(f);
  EXPECT_EQ(nlohmann::json(*f), nlohmann::json(sample()));
  EXPECT_EQ(f->discovery_server_pid, std::optional<long>(4243));
  ASSERT_EQ(f->processes.size(), 2u);
  EXPECT_EQ(f->processes[1].host, std::optional<std::string>("h1"));
  // The file as a script reads it: no host key on one host, null without a discovery server.
  const nlohmann::json j = maptr::records::read_json_object(maptr::records::fleet_file_path(tmp.path()));
  EXPECT_FALSE(j["processes"][0].contains("host"));
  EXPECT_EQ(j["processes"][1]["host"], "h1");
  FleetFile none = sample();
  none.discovery_server.reset();
  none.discovery_server_pid.reset();
  EXPECT_TRUE(nlohmann::json(none)["discovery_server_pid"].is_null());
}

TEST(FleetFile, AFleetNotStartedIsNothingOrAnErrorNamingTheFile) {
  const maptr::testing::UnitTempDir tmp("fleet_file_missing");
  EXPECT_FALSE(maptr::records::read_fleet_file(tmp.path()));
  const std::string path = maptr::records::fleet_file_path(tmp.path());
  try {
    maptr::records::require_fleet_file(tmp.path());
    ADD_FAILURE() << "no fleet.json, no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  std::ofstream(path) << R"({"domain": 3})";
  try {
    maptr::records::require_fleet_file(tmp.path());
    ADD_FAILURE() << "a fleet.json without its lease was taken";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("lease_s"), std::string::npos) << e.what();
  }
}

}  // namespace
