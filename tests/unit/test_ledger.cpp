// Wear ledger (control/level3/ledger.hpp): accrual, and its file (records/ledger_file.hpp), which a
// restarted group resumes from.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "control/level3/ledger.hpp"
#include "records/ledger_file.hpp"

namespace {

using maptr::control::Ledger;
using maptr::records::load_ledger;
using maptr::records::save_ledger;

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          (name + "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".json"))
      .string();
}

TEST(Ledger, ActiveAgentsAccrueDistanceAndTimeOthersRestartTheirTime) {
  Ledger l(4);
  l.accrue({1, 1, 0, 0}, 0.1, 0.01);
  l.accrue({1, 0, 1, 0}, 0.2, 0.01);
  EXPECT_NEAR(l.wear_m[0], 0.3, 1e-15);
  EXPECT_NEAR(l.wear_m[1], 0.1, 1e-15);
  EXPECT_NEAR(l.wear_m[2], 0.2, 1e-15);
  EXPECT_EQ(l.wear_m[3], 0.0);
  EXPECT_NEAR(l.active_time_s[0], 0.02, 1e-15);
  EXPECT_EQ(l.active_time_s[1], 0.0);  // inactive over the last tick: continuous time restarts
  EXPECT_NEAR(l.active_time_s[2], 0.01, 1e-15);
  // A shorter mask counts the missing agents as inactive.
  l.accrue({1}, 0.5, 0.01);
  EXPECT_NEAR(l.wear_m[0], 0.8, 1e-15);
  EXPECT_NEAR(l.wear_m[2], 0.2, 1e-15);
  EXPECT_EQ(l.active_time_s[2], 0.0);
}

TEST(Ledger, SavedAndLoadedIdentically) {
  const std::string path = temp_path("ledger");
  Ledger a(3);
  a.accrue({0, 1, 1}, 1.0 / 3.0, 0.01);
  a.last_t = 12.34;
  a.last_alloc_t = 10.0;
  a.n_target = 2;
  a.assignment = {0, 1, 1};
  a.decisions = 12;
  a.reallocations = 3;
  save_ledger(path, a);
  const auto b = load_ledger(path, 3);
  ASSERT_TRUE(b);
  EXPECT_EQ(b->wear_m, a.wear_m);  // exact: the file keeps every bit
  EXPECT_EQ(b->active_time_s, a.active_time_s);
  EXPECT_EQ(b->assignment, a.assignment);
  EXPECT_EQ(b->last_t, a.last_t);
  EXPECT_EQ(b->last_alloc_t, a.last_alloc_t);
  EXPECT_EQ(b->n_target, 2);
  EXPECT_EQ(b->decisions, 12u);
  EXPECT_EQ(b->reallocations, 3u);
  // A fresh ledger's "never allocated" time survives the file too.
  Ledger fresh(3);
  save_ledger(path, fresh);
  const auto c = load_ledger(path, 3);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->last_alloc_t, fresh.last_alloc_t);
  std::filesystem::remove(path);
}

TEST(Ledger, MissingFileIsNoLedgerAndBadFilesAreRefused) {
  const std::string path = temp_path("ledger");
  std::filesystem::remove(path);
  EXPECT_FALSE(load_ledger(path, 2));
  save_ledger(path, Ledger(3));
  EXPECT_THROW(load_ledger(path, 2), std::runtime_error);  // written for 3 agents per side
  EXPECT_TRUE(load_ledger(path));                          // any size when none is asked for
  std::ofstream(path) << "{\"wear_m\": [0, ";
  EXPECT_THROW(load_ledger(path, 2), std::runtime_error);
  std::filesystem::remove(path);
}

}  // namespace
