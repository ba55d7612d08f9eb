// ddmin on stub oracles with a known cause: it finds the cause, the result is 1-minimal (it
// fails, and without any one of its parts it passes), and no subset is asked twice.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "deploy/fleet/shrink.hpp"

namespace {

using maptr::deploy::shrink::ddmin;
using maptr::deploy::shrink::key;
namespace shrink = maptr::deploy::shrink;

bool contains(const std::vector<int>& s, int x) { return std::find(s.begin(), s.end(), x) != s.end(); }

void expect_one_minimal(const std::vector<int>& r, const std::function<bool(const std::vector<int>&)>& fails) {
  EXPECT_TRUE(fails(r)) << key(r);
  for (std::size_t i = 0; i < r.size(); ++i) {
    auto less = r;
    less.erase(less.begin() + static_cast<long>(i));
    EXPECT_FALSE(fails(less)) << key(r) << " without " << r[i] << " still fails";
  }
}

TEST(Shrink, FindsThreeFaultsThatBreakOnlyTogether) {
  // Like three kills of one side's agents that overlap: any two pass.
  auto fails = [](const std::vector<int>& s) { return contains(s, 2) && contains(s, 5) && contains(s, 17); };
  std::set<std::string> asked;
  int calls = 0;
  const auto r = ddmin(
      40,
      [&](const std::vector<int>& s) {
        ++calls;
        EXPECT_TRUE(asked.insert(key(s)).second) << "asked twice: " << key(s);
        return fails(s);
      });
  EXPECT_EQ(r, (std::vector<int>{2, 5, 17}));
  expect_one_minimal(r, fails);
  EXPECT_LT(calls, 100);
}

TEST(Shrink, AResultIsOneMinimalWhenSeveralCausesExist) {
  // Fails with 3 and one of 1, 8, 30: the result holds 3 and exactly one of the others.
  auto fails = [](const std::vector<int>& s) {
    return contains(s, 3) && (contains(s, 1) || contains(s, 8) || contains(s, 30));
  };
  const auto r = ddmin(32, fails);
  EXPECT_EQ(r.size(), 2u) << key(r);
  expect_one_minimal(r, fails);
}

TEST(Shrink, ASinglePartAndACaseThatNeedsNone) {
  auto one = [](const std::vector<int>& s) { return contains(s, 6); };
  EXPECT_EQ(ddmin(9, one), std::vector<int>{6});
  auto always = [](const std::vector<int>&) { return true; };
  EXPECT_TRUE(ddmin(5, always).empty());
  EXPECT_TRUE(ddmin(0, always).empty());
}

}  // namespace

TEST(Shrink, FewestAgentsKeepsEveryAgentAFaultNamesInFleetsOfFour) {
  EXPECT_EQ(shrink::fewest_agents({}), 4);
  EXPECT_EQ(shrink::fewest_agents({"central", "group-L"}), 4);
  EXPECT_EQ(shrink::fewest_agents({"L1"}), 4);   // 2 per side
  EXPECT_EQ(shrink::fewest_agents({"L2"}), 8);   // 3 per side: fours
  EXPECT_EQ(shrink::fewest_agents({"L1", "R3"}), 8);
  EXPECT_EQ(shrink::fewest_agents({"R12"}), 28);  // 13 per side -> 14
}
