// How long `launch` lets its robot processes come up before clock 0.
#include "apps/launch_command.hpp"

#include <gtest/gtest.h>

namespace dsswarm {
namespace {

TEST(LaunchStartup, TheRequestedTimeWhenSimulatingIsQuick) {
  EXPECT_DOUBLE_EQ(launch_startup_seconds(5.0, 0.0, 3, 2), 5.0);  // a scenario: nothing to simulate
  EXPECT_DOUBLE_EQ(launch_startup_seconds(5.0, 0.4, 3, 2), 5.0);  // 3 robots: well within 5 s
  EXPECT_DOUBLE_EQ(launch_startup_seconds(30.0, 1.8, 8, 2), 30.0);
}

// 8 robot processes each simulate the 8-robot swarm (1.8 s here) on 2 cores:
// 5 s was too short on a loaded machine (the robots missed 2-4 s of scans).
TEST(LaunchStartup, GrowsWithTheSimulationAndTheProcessesPerCore) {
  const double eight_on_two = launch_startup_seconds(5.0, 1.8, 8, 2);
  EXPECT_GT(eight_on_two, 4 * 1.8 * 2);  // 4 rounds of simulating, with a margin
  EXPECT_GT(eight_on_two, launch_startup_seconds(5.0, 1.8, 8, 8));
  EXPECT_GT(launch_startup_seconds(5.0, 1.8, 8, 0), 5.0);  // cores unknown: counted as one
}

}  // namespace
}  // namespace dsswarm
