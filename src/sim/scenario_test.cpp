#include "sim/scenario.hpp"

#include <gtest/gtest.h>

namespace dsswarm {
namespace {

TEST(Scenario, DefaultDemoIsAFewMinutesLong) {
  const SimulatedRun run = simulate_demo({});
  EXPECT_GE(run.log.scans.size(), 1500u);
  EXPECT_LE(run.log.scans.size(), 3000u);
  EXPECT_EQ(run.ground_truth.size(), run.log.scans.size());
  EXPECT_TRUE(run.log.warnings.empty());
  double travelled = 0;
  for (std::size_t k = 1; k < run.ground_truth.size(); ++k)
    travelled += (run.ground_truth[k].second.translation() - run.ground_truth[k - 1].second.translation()).norm();
  EXPECT_GT(travelled, 90.0);
  EXPECT_LT(travelled, 150.0);
  EXPECT_NE(run.log.source.find("demo"), std::string::npos);
}

TEST(Scenario, DemoIsReproducibleAndSeedDependent) {
  DemoConfig config;
  config.lidar.beams = 31;  // keep the test quick; only determinism is checked
  const SimulatedRun a = simulate_demo(config);
  const SimulatedRun b = simulate_demo(config);
  ASSERT_EQ(a.log.scans.size(), b.log.scans.size());
  for (std::size_t k = 0; k < a.log.scans.size(); k += 97) {
    EXPECT_EQ(a.log.scans[k].ranges, b.log.scans[k].ranges);
    EXPECT_EQ(a.ground_truth[k].second.x, b.ground_truth[k].second.x);
  }
  config.seed = 8;
  const SimulatedRun c = simulate_demo(config);
  EXPECT_NE(a.ground_truth.back().second.x, c.ground_truth.back().second.x);
}

}  // namespace
}  // namespace dsswarm
