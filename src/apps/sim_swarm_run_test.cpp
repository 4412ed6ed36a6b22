// The simulated swarm's run, whole and cut short (--duration).
#include "apps/sim_swarm_run.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

TEST(SimSwarmRun, ADurationKeepsTheStartOfTheWholeRun) {
  const SimSwarmRun whole = simulate_swarm_run({3, 1, 1, 3.0, 0.0});
  const SimSwarmRun cut = simulate_swarm_run({3, 1, 1, 3.0, 60.0});
  ASSERT_EQ(cut.streams.size(), whole.streams.size());
  ASSERT_GT(whole.streams[0].clock.back(), 60.0) << "the whole run must be longer than the cut for this test";
  for (std::size_t k = 0; k < whole.streams.size(); ++k) {
    const AgentStream& w = whole.streams[k];
    const AgentStream& c = cut.streams[k];
    ASSERT_FALSE(c.clock.empty());
    EXPECT_LE(c.clock.back(), 60.0);
    EXPECT_GT(w.clock[c.clock.size()], 60.0) << "every scan up to the duration is kept";
    ASSERT_EQ(c.scans.size(), c.clock.size());
    for (std::size_t i = 0; i < c.scans.size(); ++i) EXPECT_EQ(c.scans[i].timestamp, w.scans[i].timestamp);
    ASSERT_FALSE(cut.truth.world_poses[k].empty());
    EXPECT_LE(cut.truth.world_poses[k].back().timestamp, 60.0);
  }
  ASSERT_FALSE(cut.events.empty());
  std::size_t early = 0;
  for (const EncounterEvent& e : whole.events) early += e.time <= 60.0 ? 1 : 0;
  EXPECT_EQ(cut.events.size(), early);
  EXPECT_LT(cut.events.size(), whole.events.size());
  for (std::size_t i = 0; i < cut.events.size(); ++i) EXPECT_EQ(cut.events[i].time, whole.events[i].time);
}

TEST(SimSwarmRun, ABadDurationIsAConfigError) {
  for (const double d : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    EXPECT_THROW(simulate_swarm_run({3, 1, 1, 3.0, d}), ConfigError) << d;
}

}  // namespace
}  // namespace dsswarm
