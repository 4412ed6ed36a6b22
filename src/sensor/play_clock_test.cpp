#include "sensor/play_clock.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace dsswarm {
namespace {

TEST(PlayClock, ForwardHoldsAtTheRunningMaximumWhereStampsRunBackwards) {
  const std::vector<double> stamps = {10.0, 10.5, 10.2, 11.0, 12.0};
  EXPECT_EQ(play_clock(stamps), (std::vector<double>{0.0, 0.5, 0.5, 1.0, 2.0}));
}

TEST(PlayClock, BackwardCountsTimeDownFromTheFirstPlayedStamp) {
  // The file's last scan first; 11.2 runs the other way (forwards in time).
  const std::vector<double> stamps = {12.0, 11.0, 11.2, 10.5, 10.0};
  EXPECT_EQ(play_clock(stamps, PlayDirection::backward), (std::vector<double>{0.0, 1.0, 1.0, 1.5, 2.0}));
}

TEST(PlayClock, ScansAndEmptyRuns) {
  std::vector<LaserScan> scans(3);
  scans[0].timestamp = 5.0;
  scans[1].timestamp = 4.0;
  scans[2].timestamp = 7.0;
  EXPECT_EQ(play_clock(scans), (std::vector<double>{0.0, 0.0, 2.0}));
  EXPECT_EQ(play_clock(scans, PlayDirection::backward), (std::vector<double>{0.0, 1.0, 1.0}));
  EXPECT_TRUE(play_clock(std::vector<double>{}).empty());
}

}  // namespace
}  // namespace dsswarm
