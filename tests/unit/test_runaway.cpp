// The driver's runaway test (src/app/runaway.hpp): a run whose largest speed exceeds a hundred
// times its case's speed scale has blown up. The scale is the largest imposed or starting speed.
#include <gtest/gtest.h>

#include "app/runaway.hpp"

using namespace eulerfsi;

TEST(Runaway, TheScaleIsTheLargestImposedOrStartingSpeed) {
  CaseConfig cfg;
  cfg.flow.bulk_velocity = 1.0;
  EXPECT_DOUBLE_EQ(case_speed_scale(cfg, 0.3), 1.0);  // a pipe: its bulk velocity
  EXPECT_DOUBLE_EQ(case_speed_scale(cfg, 2.5), 2.5);  // a start faster than the bulk
  cfg.flow.wall_velocity = {-3.0, 2.0};
  EXPECT_DOUBLE_EQ(case_speed_scale(cfg, 0.0), 3.0);  // a wall faster than both
  cfg.flow.frame_velocity = -4.0;
  EXPECT_DOUBLE_EQ(case_speed_scale(cfg, 0.0), 4.0);  // a grid moving at a fixed speed
  cfg.flow.frame_follows_particle = true;             // a grid following the particle: no scale of its own
  EXPECT_DOUBLE_EQ(case_speed_scale(cfg, 0.0), 3.0);
}

TEST(Runaway, OnlyBeyondAHundredTimesTheScale) {
  EXPECT_FALSE(speed_ran_away(99.0, 1.0));
  EXPECT_TRUE(speed_ran_away(101.0, 1.0));
  EXPECT_FALSE(speed_ran_away(299.0, 3.0));
  EXPECT_TRUE(speed_ran_away(301.0, 3.0));
  // nothing moves in the case and nothing moved at the start: no scale, no verdict
  EXPECT_FALSE(speed_ran_away(1e6, 0.0));
}
