// The launcher's control commands and its plant clock (deploy/fleet/control_fifo.hpp,
// deploy/fleet/plant_clock.hpp).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "deploy/fleet/control_fifo.hpp"
#include "deploy/fleet/plant_clock.hpp"
#include "tests/unit/unit_temp_dir.hpp"

using namespace maptr::deploy::fleet;

TEST(FleetControlLines, CompleteLinesBecomeCommands) {
  CommandLines lines;
  const auto c = lines.feed("kill L1\nrestart group-R\n");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_TRUE(c[0].valid);
  EXPECT_EQ(c[0].action, "kill");
  EXPECT_EQ(c[0].target, "L1");
  EXPECT_EQ(c[1].action, "restart");
  EXPECT_EQ(c[1].target, "group-R");
}

TEST(FleetControlLines, PartialLineWaitsForItsEnd) {
  CommandLines lines;
  EXPECT_TRUE(lines.feed("resta").empty());
  EXPECT_TRUE(lines.feed("rt R").empty());
  const auto c = lines.feed("3\nkill ");
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].action, "restart");
  EXPECT_EQ(c[0].target, "R3");
  const auto d = lines.feed("central\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].target, "central");
}

TEST(FleetControlLines, UnknownCommandsAndBlankLinesAreInvalid) {
  CommandLines lines;
  const auto c = lines.feed("stop L1\n\n  kill   L2  \n");
  ASSERT_EQ(c.size(), 3u);
  EXPECT_FALSE(c[0].valid);
  EXPECT_EQ(c[0].action, "stop");
  EXPECT_FALSE(c[1].valid);
  EXPECT_TRUE(c[2].valid);
  EXPECT_EQ(c[2].target, "L2");
}

TEST(FleetControlFifo, CommandSentToARunDirIsRead) {
  const maptr::testing::UnitTempDir tmp("fleet_fifo");
  const std::string dir = tmp.path();
  std::filesystem::create_directories(dir);
  EXPECT_THROW(maptr::deploy::send_command(dir, "kill", "L1"), std::runtime_error) << "no reader yet";
  {
    ControlFifo fifo(dir);
    maptr::deploy::send_command(dir, "kill", "L1");
    const auto c = fifo.read();
    ASSERT_EQ(c.size(), 1u);
    EXPECT_EQ(c[0].target, "L1");
    EXPECT_TRUE(fifo.read().empty());
  }
  EXPECT_FALSE(std::filesystem::exists(control_fifo_path(dir))) << "removed with its reader";
}

namespace {
GuidPrefix prefix(uint8_t b) {
  GuidPrefix p{};
  p.fill(b);
  return p;
}
}  // namespace

TEST(FleetPlantClock, OnlyThePlantsTicksMoveTheClock) {
  PlantClock clock;
  EXPECT_FALSE(clock.on_tick(prefix(1), {5.0, 1.0, 10.0, 2, 3})) << "plant not known yet";
  clock.learn_plant(prefix(1));
  EXPECT_TRUE(clock.on_tick(prefix(1), {0.5, 0.2, 3.0, 4, 4}));
  EXPECT_FALSE(clock.on_tick(prefix(2), {99.0, 9.0, 9e9, 0, 0})) << "a forged tick";
  EXPECT_DOUBLE_EQ(clock.state().t, 0.5);
  EXPECT_DOUBLE_EQ(clock.state().v_x, 0.2);
  EXPECT_EQ(clock.state().active_L, 4);
  EXPECT_EQ(clock.rejected(), 2);
  EXPECT_FALSE(clock.from_plant(prefix(2)));
  EXPECT_TRUE(clock.from_plant(prefix(1)));
  clock.on_gate(0.7);
  EXPECT_DOUBLE_EQ(clock.state().t, 0.7);
  clock.on_gate(0.6);
  EXPECT_DOUBLE_EQ(clock.state().t, 0.7) << "a gate never moves the clock back";
}
