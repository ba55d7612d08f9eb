// The plant's watch over the groups' wear ledgers (plant/wear_watch.hpp).
#include <gtest/gtest.h>

#include "plant/wear_watch.hpp"

namespace {

using maptr::plant::WearWatch;

TEST(PlantWearWatch, GrowingLedgersAreNoRegression) {
  WearWatch w;
  w.on_status(0, {0.0, 0.0}, 0.01);
  w.on_status(0, {0.1, 0.0}, 0.02);
  w.on_status(0, {0.1, 0.2}, 0.03);
  w.on_status(1, {5.0}, 0.03);
  EXPECT_EQ(w.regressions(0), 0);
  const auto j = w.json();
  EXPECT_EQ(j["L"]["wear_m"], nlohmann::json({0.1, 0.2}));
  EXPECT_EQ(j["R"]["wear_m"], nlohmann::json({5.0}));
  EXPECT_TRUE(j["L"]["first_regression_s"].is_null());
}

TEST(PlantWearWatch, ADropIsCountedWithItsSizeAndTime) {
  WearWatch w;
  w.on_status(1, {1.0, 2.0}, 4.0);
  w.on_status(1, {1.0, 1.75}, 4.5);         // a restarted group that lost 0.25 m
  w.on_status(1, {1.0 - 1e-12, 1.8}, 4.6);  // rounding, not a regression
  w.on_status(1, {0.5, 1.8}, 5.0);
  EXPECT_EQ(w.regressions(1), 2);
  EXPECT_EQ(w.regressions(0), 0);
  const auto j = w.json()["R"];
  EXPECT_NEAR(j["largest_drop_m"].get<double>(), 0.5, 1e-9);
  EXPECT_DOUBLE_EQ(j["first_regression_s"].get<double>(), 4.5);
}

}  // namespace
