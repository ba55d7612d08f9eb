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
#include <nlohmann/json.hpp>

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
  using maptr::records::parse_registry_entry;
  using maptr::records::registry_entry_text;
  FleetEntry e{"/data/run", "loop", 4242, 777, 12, 1.5e9};
  const auto back = parse_registry_entry(registry_entry_text(e));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->run_dir, "/data/run");
  EXPECT_EQ(back->pid, 4242);
  EXPECT_EQ(back->start_ticks, 777);
  EXPECT_DOUBLE_EQ(back->started_unix_s, 1.5e9);
  EXPECT_FALSE(parse_registry_entry(R"({"run_dir": "/x"})"));
  EXPECT_FALSE(parse_registry_entry("not json"));
  FleetEntry relative = e;
  relative.run_dir = "runs/x";
  EXPECT_FALSE(parse_registry_entry(registry_entry_text(relative)));
  FleetEntry init = e;
  init.pid = 1;
  EXPECT_FALSE(parse_registry_entry(registry_entry_text(init)));
  auto wrong_type = nlohmann::json::parse(registry_entry_text(e));
  wrong_type["pid"] = "4242";
  EXPECT_FALSE(parse_registry_entry(wrong_type.dump()));
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
  ASSERT_TRUE(maptr::records::write_registry_entry(entry, FleetEntry{d.path, "gone", child, 5, 0, 1.0}));
  // The same pid with another start time (a reused pid) is gone too.
  const std::string reused = registry_dir() + "/" + std::to_string(getpid()) + ".json";
  ASSERT_TRUE(maptr::records::write_registry_entry(
      reused, FleetEntry{d.path, "reused", getpid(), process_start_ticks(getpid()) + 1, 0, 2.0}));
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
