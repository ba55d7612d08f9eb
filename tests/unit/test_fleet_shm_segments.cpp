// Fast DDS shared-memory segments without owner (deploy/fleet/shm_segments.hpp): names, maps
// lines, and which segments a sweep removes.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "deploy/fleet/shm_segments.hpp"

namespace fs = std::filesystem;
using namespace maptr::deploy::fleet;

namespace {

class ShmSegments : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("maptr-seg-test-" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override {
    for (int fd : held) ::close(fd);
    fs::remove_all(dir);
  }
  /// A segment and its lock file, last modified age_s ago.
  void make(const std::string& name, double age_s) {
    for (const std::string& f : {name, name + "_el"}) {
      std::ofstream(dir / f) << "x";
      const timespec t = {time(nullptr) - static_cast<time_t>(age_s), 0};
      const timespec times[2] = {t, t};
      ASSERT_EQ(utimensat(AT_FDCWD, (dir / f).c_str(), times, 0), 0);
    }
  }
  /// Holds the segment's lock as a live owner does.
  void hold(const std::string& name) {
    const int fd = ::open((dir / (name + "_el")).c_str(), O_RDONLY);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
    held.push_back(fd);
  }
  bool present(const std::string& name) const {
    return fs::exists(dir / name) || fs::exists(dir / (name + "_el"));
  }

  fs::path dir;
  std::vector<int> held;
};

TEST(ShmSegmentNames, SegmentsAndTheirLocksButNotPorts) {
  EXPECT_EQ(segment_name("fastrtps_03833ee14bd335f4"), "fastrtps_03833ee14bd335f4");
  EXPECT_EQ(segment_name("fastrtps_03833ee14bd335f4_el"), "fastrtps_03833ee14bd335f4");
  EXPECT_EQ(segment_name("fastrtps_port7411"), "");
  EXPECT_EQ(segment_name("fastrtps_port7411_el"), "");
  EXPECT_EQ(segment_name("sem.fastrtps_port7411_mutex"), "");
  EXPECT_EQ(segment_name("fastrtps_03833ee14bd335f"), "");   // 15 characters
  EXPECT_EQ(segment_name("fastrtps_03833EE14bd335f4"), "");  // not the tool's alphabet
  EXPECT_EQ(segment_name("fastrtps_03833ee14bd335f4_sl"), "");
}

TEST(ShmSegmentNames, FromMapsLines) {
  EXPECT_EQ(segment_in_maps_line("7f0c1a000000-7f0c1a400000 rw-s 00000000 00:1a 123 "
                                 "/dev/shm/fastrtps_a35202b7837845e3"),
            "fastrtps_a35202b7837845e3");
  EXPECT_EQ(segment_in_maps_line("7f0c1a000000-7f0c1a400000 rw-s 00000000 00:1a 123 "
                                 "/dev/shm/fastrtps_a35202b7837845e3 (deleted)"),
            "fastrtps_a35202b7837845e3");
  EXPECT_EQ(
      segment_in_maps_line("7f0c1a000000-7f0c1a400000 rw-s 00000000 00:1a 9 /dev/shm/fastrtps_port7411"), "");
  EXPECT_EQ(segment_in_maps_line("7f0c1a000000-7f0c1a021000 rw-p 00000000 00:00 0 [heap]"), "");
}

TEST(ShmSegmentNames, TheSegmentsAProcessMaps) {
  const std::string name =
      "fastrtps_zz" + std::to_string(1000000000 + getpid() % 1000000000).substr(0, 10) + "tt00";
  ASSERT_EQ(segment_name(name), name);
  const std::string path = "/dev/shm/" + name;
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL, 0600);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::ftruncate(fd, 4096), 0);
  void* p = ::mmap(nullptr, 4096, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  ::close(fd);
  ASSERT_NE(p, MAP_FAILED);
  EXPECT_EQ(segments_mapped_by(getpid()).count(name), 1u);
  ::munmap(p, 4096);
  ::unlink(path.c_str());
  EXPECT_EQ(segments_mapped_by(getpid()).count(name), 0u);
}

TEST_F(ShmSegments, AnOrphanOldEnoughIsRemovedALiveOneIsKept) {
  make("fastrtps_0000000000000001", 60);  // owner gone
  make("fastrtps_0000000000000002", 60);  // owner alive
  make("fastrtps_0000000000000003", 0);   // owner gone, but just created
  hold("fastrtps_0000000000000002");
  const auto gone = remove_orphan_segments(dir.string(), 2.0);
  EXPECT_EQ(gone, std::vector<std::string>{"fastrtps_0000000000000001"});
  EXPECT_FALSE(present("fastrtps_0000000000000001"));
  EXPECT_TRUE(present("fastrtps_0000000000000002"));
  EXPECT_TRUE(present("fastrtps_0000000000000003"));
  // A fleet's own segments go whatever their age.
  EXPECT_EQ(remove_orphan_segments(dir.string(), 2.0, {"fastrtps_0000000000000003"}),
            std::vector<std::string>{"fastrtps_0000000000000003"});
}

TEST_F(ShmSegments, AProcessKilledWithSigkillLeavesAnOrphan) {
  make("fastrtps_00000000000000aa", 60);
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const int fd = ::open((dir / "fastrtps_00000000000000aa_el").c_str(), O_RDONLY);
    ::flock(fd, LOCK_EX);
    char c = 1;
    if (::write(ready[1], &c, 1) != 1) _exit(1);
    for (;;) ::pause();
  }
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  EXPECT_FALSE(segment_orphaned(dir.string(), "fastrtps_00000000000000aa"));
  ::kill(child, SIGKILL);
  ::waitpid(child, nullptr, 0);
  ::close(ready[0]);
  ::close(ready[1]);
  EXPECT_TRUE(segment_orphaned(dir.string(), "fastrtps_00000000000000aa"));
  EXPECT_EQ(remove_orphan_segments(dir.string(), 2.0).size(), 1u);
  EXPECT_FALSE(present("fastrtps_00000000000000aa"));
}

TEST_F(ShmSegments, AnEmptySegmentWithoutLockFileIsRemovedOnceOldEnough) {
  // A process killed between creating a segment and sizing it leaves an empty file, no lock.
  for (const std::string f : {"fastrtps_00000000000000c1", "fastrtps_00000000000000c2"}) {
    std::ofstream(dir / f).close();
    const timespec t = {time(nullptr) - (f.back() == '1' ? 60 : 0), 0};
    const timespec times[2] = {t, t};
    ASSERT_EQ(utimensat(AT_FDCWD, (dir / f).c_str(), times, 0), 0);
  }
  EXPECT_EQ(remove_orphan_segments(dir.string(), 2.0), std::vector<std::string>{"fastrtps_00000000000000c1"});
  EXPECT_FALSE(present("fastrtps_00000000000000c1"));
  EXPECT_TRUE(present("fastrtps_00000000000000c2")) << "one just being created is kept";
}

TEST_F(ShmSegments, NoLockFileIsNoOrphan) {
  std::ofstream(dir / "fastrtps_00000000000000bb") << "x";
  EXPECT_FALSE(segment_orphaned(dir.string(), "fastrtps_00000000000000bb"));
  EXPECT_TRUE(remove_orphan_segments(dir.string(), 0.0).empty());
}

}  // namespace
