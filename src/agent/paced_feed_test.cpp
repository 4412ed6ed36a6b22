#include "agent/paced_feed.hpp"
#include "agent/paced_feed_test_util.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace dsswarm::agent {
namespace {

using namespace std::chrono_literals;

std::vector<LaserScan> numbered(int n) {
  std::vector<LaserScan> scans(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) scans[static_cast<std::size_t>(i)].timestamp = 100.0 + 0.1 * i;
  return scans;
}

TEST(PacedFeed, PlaysInRealTimeTimesTheRate) {
  const auto start = std::chrono::steady_clock::now();
  PacedFeed feed(numbered(11), std::vector<double>{0, .1, .2, .3, .4, .5, .6, .7, .8, .9, 1.0}, paced(5.0, 8));
  int got = 0;
  while (!feed.exhausted())
    if (feed.next(100ms)) ++got;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(got, 11);
  EXPECT_EQ(feed.dropped(), 0u);
  EXPECT_GE(seconds, 0.19);  // 1 s of log at 5×
  EXPECT_LT(seconds, 2.0);
}

TEST(PacedFeed, ARobotThatFallsBehindLosesTheOldestScansNotMemory) {
  PacedFeed feed(numbered(50), std::vector<double>(50, 0.0), paced(1.0, 4));
  while (feed.received() < 50) std::this_thread::sleep_for(5ms);
  EXPECT_EQ(feed.dropped(), 46u);
  const auto first = feed.next(10ms);
  ASSERT_TRUE(first);
  EXPECT_DOUBLE_EQ(first->timestamp, 100.0 + 0.1 * 46);  // the newest four are kept
}

TEST(PacedFeed, PlayClockHoldsAtTheRunningMaximum) {
  std::vector<LaserScan> scans = numbered(4);
  scans[2].timestamp = 100.05;  // runs backwards
  const std::vector<double> clock = play_clock(scans);
  EXPECT_DOUBLE_EQ(clock[1], clock[2]);
  EXPECT_NEAR(clock[3], 0.3, 1e-9);
}

}  // namespace
}  // namespace dsswarm::agent
