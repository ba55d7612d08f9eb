// Stale Fast DDS port files: which are removed and which are kept (comm/posix/shm_files.hpp).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "comm/posix/shm_files.hpp"

namespace fs = std::filesystem;
using maptr::comm::remove_unused_shm_ports;

namespace {

class ShmFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("maptr-shm-test-" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  /// Creates a file of `bytes` bytes, last modified `age_s` seconds ago.
  fs::path make(const std::string& name, double age_s, std::size_t bytes = 4096) {
    const fs::path p = dir / name;
    std::ofstream(p) << std::string(bytes, 'x');
    const timespec t = {time(nullptr) - static_cast<time_t>(age_s), 0};
    const timespec times[2] = {t, t};
    EXPECT_EQ(utimensat(AT_FDCWD, p.c_str(), times, 0), 0);
    return p;
  }
  void make_port(int n, double age_s) {
    make("fastrtps_port" + std::to_string(n), age_s);
    make("fastrtps_port" + std::to_string(n) + "_el", age_s, 0);
    make("sem.fastrtps_port" + std::to_string(n) + "_mutex", age_s, 32);
  }
  bool has_port_files(int n) const {
    return fs::exists(dir / ("fastrtps_port" + std::to_string(n))) ||
           fs::exists(dir / ("fastrtps_port" + std::to_string(n) + "_el")) ||
           fs::exists(dir / ("sem.fastrtps_port" + std::to_string(n) + "_mutex"));
  }

  fs::path dir;
};

}  // namespace

TEST_F(ShmFiles, UnmappedOldPortsGoMappedAndYoungOnesAndOtherFilesStay) {
  make_port(7411, 3600);  // stale: old, nobody maps it
  make_port(7413, 3600);  // old, but this process maps its segment below
  make_port(7415, 1);     // just created: not mapped yet, maybe about to be
  make("fastrtps_0123456789abcdef", 3600);     // a participant segment: `fastdds shm clean`'s job
  make("fastrtps_0123456789abcdef_el", 3600, 0);
  make("fastrtps_portal", 3600);                // not a port file
  make("sem.fastrtps_port7417_other", 3600);    // not a port file either

  const int fd = open((dir / "fastrtps_port7413").c_str(), O_RDWR);
  ASSERT_GE(fd, 0);
  void* m = mmap(nullptr, 4096, PROT_READ, MAP_SHARED, fd, 0);
  ASSERT_NE(m, MAP_FAILED);
  close(fd);

  const auto r = remove_unused_shm_ports(dir.string(), 10.0);
  munmap(m, 4096);

  EXPECT_EQ(r.ports_removed, 1);
  EXPECT_EQ(r.ports_in_use, 1);
  EXPECT_EQ(r.ports_too_young, 1);
  EXPECT_FALSE(has_port_files(7411));
  EXPECT_TRUE(fs::exists(dir / "fastrtps_port7413"));
  EXPECT_TRUE(fs::exists(dir / "fastrtps_port7413_el"));
  EXPECT_TRUE(fs::exists(dir / "sem.fastrtps_port7413_mutex"));
  EXPECT_TRUE(fs::exists(dir / "fastrtps_port7415"));
  EXPECT_TRUE(fs::exists(dir / "fastrtps_0123456789abcdef"));
  EXPECT_TRUE(fs::exists(dir / "fastrtps_0123456789abcdef_el"));
  EXPECT_TRUE(fs::exists(dir / "fastrtps_portal"));
  EXPECT_TRUE(fs::exists(dir / "sem.fastrtps_port7417_other"));

  // Unmapped now: the second sweep takes it; the young one stays until it is old enough.
  const auto r2 = remove_unused_shm_ports(dir.string(), 10.0);
  EXPECT_EQ(r2.ports_removed, 1);
  EXPECT_FALSE(has_port_files(7413));
  EXPECT_TRUE(has_port_files(7415));
  EXPECT_EQ(remove_unused_shm_ports(dir.string(), 0.0).ports_removed, 1);
  EXPECT_FALSE(has_port_files(7415));
}

TEST_F(ShmFiles, AMissingDirectoryIsNotAnError) {
  const auto r = remove_unused_shm_ports((dir / "nope").string(), 10.0);
  EXPECT_EQ(r.ports_removed, 0);
  EXPECT_EQ(r.ports_in_use, 0);
}

TEST_F(ShmFiles, APortWhoseLockFileIsHeldStays) {
  make_port(7419, 3600);
  const int fd = open((dir / "fastrtps_port7419_el").c_str(), O_RDONLY);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(flock(fd, LOCK_SH | LOCK_NB), 0);
  // flock locks belong to the open file description: take it in a child, so that this
  // process's own probe in remove_unused_shm_ports() conflicts with it.
  int pipefd[2];
  ASSERT_EQ(pipe(pipefd), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    close(pipefd[1]);
    char c;
    (void)!read(pipefd[0], &c, 1);  // hold the inherited lock until the parent is done
    _exit(0);
  }
  close(pipefd[0]);
  close(fd);  // the child's copy keeps the lock
  const auto r = remove_unused_shm_ports(dir.string(), 10.0);
  EXPECT_EQ(r.ports_in_use, 1);
  EXPECT_EQ(r.ports_removed, 0);
  EXPECT_TRUE(has_port_files(7419));
  close(pipefd[1]);
  waitpid(child, nullptr, 0);
  EXPECT_EQ(remove_unused_shm_ports(dir.string(), 10.0).ports_removed, 1);
  EXPECT_FALSE(has_port_files(7419));
}

TEST(RtpsPorts, FollowTheWellKnownPortMapping) {
  // RTPS 2.x, section 9.6.1.1: PB + DG * domain + d_ + PG * participant_id.
  const auto p0 = maptr::comm::rtps_ports(0, 0);
  EXPECT_EQ(p0, (std::set<int>{7400, 7401, 7410, 7411}));
  const auto p = maptr::comm::rtps_ports(159, 4);
  EXPECT_EQ(p.size(), 2u + 2u * 5u);
  EXPECT_TRUE(p.count(7400 + 250 * 159));          // metatraffic multicast
  EXPECT_TRUE(p.count(7400 + 250 * 159 + 18));     // id 4, metatraffic unicast
  EXPECT_TRUE(p.count(7400 + 250 * 159 + 19));     // id 4, user unicast
  EXPECT_FALSE(p.count(7400 + 250 * 159 + 20));    // id 5: not asked for
}

TEST_F(ShmFiles, AFleetRemovesOnlyItsOwnPortsButAtAnyAge) {
  make_port(47168, 0);  // this fleet's, just released
  make_port(47418, 0);  // another domain's, just as young
  const std::set<int> mine = maptr::comm::rtps_ports(159, 4);
  const auto r = remove_unused_shm_ports(dir.string(), 10.0, mine);
  EXPECT_EQ(r.ports_removed, 1);
  EXPECT_FALSE(has_port_files(47168));
  EXPECT_TRUE(has_port_files(47418));
}
