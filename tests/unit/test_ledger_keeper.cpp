// The plant's keeper of the groups' wear ledgers (plant/ledger_keeper.hpp): what a restarted
// group is handed, to which start, until when, and the files at the end.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "comm/lockstep/wear_ledger.hpp"
#include "plant/ledger_keeper.hpp"
#include "records/ledger_file.hpp"

namespace {

using maptr::plant::LedgerKeeper;
namespace msg = maptr::msg;

msg::GroupStatus status(double wear0, uint64_t reallocations) {
  maptr::control::Ledger l(3);
  l.wear_m = {wear0, 1.0, 0.0};
  l.assignment = {1, 1, 0};
  l.reallocations = reallocations;
  msg::GroupStatus g;
  g.active(l.assignment);
  g.ledger(maptr::comm::to_msg(l));
  return g;
}

TEST(LedgerKeeper, ARestartedGroupIsHandedItsSidesLastLedgerUntilItAnswers) {
  LedgerKeeper k;
  msg::PlantTick t;
  k.on_status(1, status(2.0, 1));
  k.on_status(1, status(3.5, 2));  // the last one taken counts
  k.fill(t);
  EXPECT_TRUE(t.ledgers().empty());  // nobody restarted: the ticks carry nothing
  k.on_started(1, 42);
  k.fill(t);
  ASSERT_EQ(t.ledgers().size(), 1u);
  EXPECT_EQ(t.ledgers()[0].side(), msg::SIDE_R);
  EXPECT_EQ(t.ledgers()[0].for_participant(), 42);
  EXPECT_EQ(t.ledgers()[0].ledger().wear_m()[0], 3.5);
  EXPECT_EQ(t.ledgers()[0].ledger().reallocations(), 2u);
  EXPECT_EQ(t.ledgers()[0].assignment(), (std::vector<uint8_t>{1, 1, 0}));
  k.fill(t);
  EXPECT_EQ(t.ledgers().size(), 1u);  // every tick until the new start answers
  k.on_status(1, status(3.6, 2));     // its answer
  k.fill(t);
  EXPECT_TRUE(t.ledgers().empty());
}

TEST(LedgerKeeper, AGroupNeverHeardFromLeavesNothingToHandOverAndNoFile) {
  LedgerKeeper k;
  msg::PlantTick t;
  k.on_started(0, 40);
  k.fill(t);
  EXPECT_TRUE(t.ledgers().empty());
  k.on_started(1, 0);  // the launcher did not say which start: any start of group-R takes it
  k.on_status(1, status(1.0, 1));
  k.on_started(1, 0);
  k.fill(t);
  ASSERT_EQ(t.ledgers().size(), 1u);
  EXPECT_EQ(t.ledgers()[0].for_participant(), -1);
  const std::string dir = (std::filesystem::temp_directory_path() / "maptr-ledger-keeper").string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  k.save(dir);
  EXPECT_FALSE(std::filesystem::exists(maptr::records::ledger_path(dir, 0)));
  const auto r = maptr::records::load_ledger(maptr::records::ledger_path(dir, 1), 3);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->wear_m, (std::vector<double>{1.0, 1.0, 0.0}));
  EXPECT_EQ(r->assignment, (std::vector<uint8_t>{1, 1, 0}));
  EXPECT_EQ(r->reallocations, 1u);
  std::filesystem::remove_all(dir);
}

}  // namespace
