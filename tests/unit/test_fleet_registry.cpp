// The registry of running fleets: where it lives, what an entry holds, that a launcher's entry
// lives as long as its registration, that the entry of a launcher that is gone is removed, and
// the simulated time read from the end of a trace.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "deploy/fleet/control_fifo.hpp"
#include "deploy/fleet/registry.hpp"

namespace {

namespace fs = std::filesystem;
using namespace maptr::deploy::fleet;

struct Dir {
  std::string path;
  Dir() {
    char t[] = "/tmp/maptr-registry-XXXXXX";
    path = mkdtemp(t);
  }
  ~Dir() { fs::remove_all(path); }
};

/// XDG_RUNTIME_DIR set for the test's length.
struct RuntimeDir {
  explicit RuntimeDir(const std::string& d) { setenv("XDG_RUNTIME_DIR", d.c_str(), 1); }
  ~RuntimeDir() { unsetenv("XDG_RUNTIME_DIR"); }
};

TEST(FleetRegistry, LivesInTheUsersRuntimeDirectory) {
  EXPECT_EQ(registry_dir("/run/user/1000", 1000), "/run/user/1000/maptr/fleets");
  EXPECT_EQ(registry_dir(nullptr, 0), "/run/maptr/fleets");
  EXPECT_EQ(registry_dir(nullptr, 1000), "/tmp/maptr-1000/fleets");
  EXPECT_EQ(registry_dir("relative", 1000), "/tmp/maptr-1000/fleets");  // not a path: ignored
}

TEST(FleetRegistry, AnEntryReadsBackAndAMalformedOneIsIgnored) {
  FleetEntry e{"/data/run", "loop", 4242, 777, 12, 1.5e9};
  const auto back = fleet_entry_from(to_json(e));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->run_dir, "/data/run");
  EXPECT_EQ(back->pid, 4242);
  EXPECT_EQ(back->start_ticks, 777);
  EXPECT_FALSE(fleet_entry_from(nlohmann::json{{"run_dir", "/x"}}));
  auto relative = to_json(e);
  relative["run_dir"] = "runs/x";
  EXPECT_FALSE(fleet_entry_from(relative));
  auto init = to_json(e);
  init["pid"] = 1;
  EXPECT_FALSE(fleet_entry_from(init));
}

TEST(FleetRegistry, ARegisteredFleetIsListedUntilItsRegistrationEnds) {
  Dir d;
  RuntimeDir rt(d.path);
  const std::string run = d.path + "/somewhere/run";
  fs::create_directories(run);
  ControlFifo fifo(run);
  {
    FleetRegistration reg(run, "mine", 17);
    ASSERT_FALSE(reg.path().empty());
    const auto fleets = running_fleets();
    ASSERT_EQ(fleets.size(), 1u);
    EXPECT_EQ(fleets[0].run_dir, run);
    EXPECT_EQ(fleets[0].scenario, "mine");
    EXPECT_EQ(fleets[0].domain, 17);
    EXPECT_EQ(fleets[0].pid, getpid());
  }
  EXPECT_TRUE(running_fleets().empty());
  EXPECT_TRUE(fs::is_empty(d.path + "/maptr/fleets"));
}

TEST(FleetRegistry, TheEntryOfALauncherThatIsGoneIsRemoved) {
  Dir d;
  RuntimeDir rt(d.path);
  const pid_t child = fork();
  if (child == 0) _exit(0);
  ASSERT_GT(child, 0);
  waitpid(child, nullptr, 0);  // a pid that no longer runs
  fs::create_directories(registry_dir());
  const std::string entry = registry_dir() + "/" + std::to_string(child) + ".json";
  std::ofstream(entry) << to_json(FleetEntry{d.path, "gone", child, 5, 0, 1.0}).dump();
  // The same pid with another start time (a reused pid) is gone too.
  const std::string reused = registry_dir() + "/" + std::to_string(getpid()) + ".json";
  std::ofstream(reused) << to_json(FleetEntry{d.path, "reused", getpid(), process_start_ticks(getpid()) + 1, 0, 2.0}).dump();
  EXPECT_TRUE(running_fleets().empty());
  EXPECT_FALSE(fs::exists(entry));
  EXPECT_FALSE(fs::exists(reused));
}

TEST(FleetRegistry, TheSimulatedTimeIsTheTracesLastCompleteRow) {
  Dir d;
  EXPECT_TRUE(std::isnan(trace_time_s(d.path)));
  std::ofstream(d.path + "/trace.csv") << "tick,t_s,x_m\n0,0.000000,0\n1,0.010000,0\n2,0.02";  // a row being written
  EXPECT_DOUBLE_EQ(trace_time_s(d.path), 0.01);
  EXPECT_GT(process_start_ticks(getpid()), 0);
  EXPECT_EQ(process_start_ticks(999999999), -1);
}

}  // namespace
