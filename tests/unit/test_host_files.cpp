// A host's run folder (deploy/fleet/host_files.hpp): what the launcher ships to a host with a
// disk of its own, how it tells a shared disk, and how a host's copy merges into its folder.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "deploy/fleet/host_files.hpp"

namespace {

namespace fs = std::filesystem;
using maptr::deploy::fleet::HostDisk;

class Dir {
 public:
  Dir() {
    std::string t = (fs::temp_directory_path() / "maptr-host-files-XXXXXX").string();
    path_ = mkdtemp(t.data());
  }
  ~Dir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::string text(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write(const std::string& path, const std::string& content) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path) << content;
}

// A command prefix that runs on this machine ("env"): the host's run folder is the path given.
const std::vector<std::string> kHere = {"env"};

TEST(HostFiles, AHostWithADiskOfItsOwnGetsTheScenarioAndALogsFolder) {
  Dir d;
  const std::string run = d.path() + "/run";
  HostDisk disk = HostDisk::kSame;
  const std::string yaml = "name: it's \"quoted\"\nagents: 8\n";
  EXPECT_EQ(maptr::deploy::fleet::ship_run_files(kHere, run, {{"scenario.yaml", yaml}}, disk), "");
  EXPECT_EQ(disk, HostDisk::kOwn);
  EXPECT_EQ(text(run + "/scenario.yaml"), yaml);  // byte for byte, quotes and all
  EXPECT_TRUE(fs::is_directory(run + "/logs"));
}

TEST(HostFiles, AHostThatSeesTheLaunchersMarkerSharesItsDiskAndGetsNothing) {
  Dir d;
  write(d.path() + "/" + maptr::deploy::fleet::kLauncherMarker, "1\n");
  HostDisk disk = HostDisk::kSame;
  EXPECT_EQ(maptr::deploy::fleet::ship_run_files(kHere, d.path(), {{"scenario.yaml", "x: 1\n"}}, disk), "");
  EXPECT_EQ(disk, HostDisk::kShared);
  EXPECT_FALSE(fs::exists(d.path() + "/scenario.yaml"));
  // No prefix: the launcher's own machine.
  EXPECT_EQ(maptr::deploy::fleet::ship_run_files({}, d.path(), {}, disk), "");
  EXPECT_EQ(disk, HostDisk::kSame);
}

TEST(HostFiles, AFolderThatCannotBeWrittenIsAProblemNamingIt) {
  HostDisk disk = HostDisk::kSame;
  const std::string why =
      maptr::deploy::fleet::ship_run_files(kHere, "/proc/maptr-no-such", {{"scenario.yaml", "x: 1\n"}}, disk);
  EXPECT_NE(why.find("/proc/maptr-no-such"), std::string::npos) << why;
}

TEST(HostFiles, AHostsCopyMergesIntoTheRunFolder) {
  Dir d;
  const std::string run = d.path() + "/run", copy = d.path() + "/copy";
  write(run + "/logs/launcher.log", "launcher\n");
  write(run + "/level2-L.csv", "t_s,n\n1,2\n");
  write(run + "/logs/group-L.log", "on h1\n");
  write(run + "/summary.json", "{\"launcher\": true}\n");
  write(copy + "/trace.csv", "tick,t_s\n0,0\n");
  write(copy + "/logs/L3.log", "L3\n");
  write(copy + "/logs/group-L.log", "on h2\n");              // group-L failed over to this host
  write(copy + "/level2-L.csv", "t_s,n\n5,3\n");             // its Level-2 log, continued
  write(copy + "/summary.json", "{\"launcher\": false}\n");  // never taken over the launcher's
  EXPECT_EQ(maptr::deploy::fleet::merge_host_folder(copy, run), 4);
  EXPECT_EQ(text(run + "/trace.csv"), "tick,t_s\n0,0\n");
  EXPECT_EQ(text(run + "/logs/L3.log"), "L3\n");
  EXPECT_EQ(text(run + "/logs/group-L.log"), "on h1\non h2\n");
  EXPECT_EQ(text(run + "/level2-L.csv"), "t_s,n\n1,2\n5,3\n");  // one header
  EXPECT_EQ(text(run + "/summary.json"), "{\"launcher\": true}\n");
  EXPECT_EQ(text(run + "/logs/launcher.log"), "launcher\n");
}

}  // namespace
