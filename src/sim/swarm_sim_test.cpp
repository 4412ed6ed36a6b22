#include "sim/swarm_sim.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "common/errors.hpp"
#include "sim/proximity.hpp"

namespace dsswarm {
namespace {

// Few beams: these tests check the robots' motion and bookkeeping, which do
// not depend on the lidar resolution, and stay fast.
SwarmSimConfig quick_config(int robots, std::uint64_t seed) {
  SwarmSimConfig config;
  config.robots = robots;
  config.world = swarm_world_config(robots);
  config.lidar.beams = 8;
  config.seed = seed;
  return config;
}

// Rooms a robot's true path enters (well inside the walls, not just the doorway).
std::set<std::size_t> rooms_entered(const World& world, const SimulatedRun& run) {
  std::set<std::size_t> rooms;
  for (const auto& [time, pose] : run.ground_truth)
    for (std::size_t k = 0; k < world.layout().rooms.size(); ++k)
      if (world.layout().rooms[k].area.expanded(-0.5).contains(pose.translation())) rooms.insert(k);
  return rooms;
}

double heading_at_start(const SimulatedRun& run) { return run.ground_truth.front().second.theta; }

// The checks every simulated swarm must pass.
void expect_well_formed(const SwarmSimConfig& config, const SimulatedSwarm& swarm) {
  const auto robots = static_cast<std::size_t>(config.robots);
  ASSERT_EQ(swarm.runs.size(), robots);
  ASSERT_EQ(swarm.names.size(), robots);
  ASSERT_EQ(swarm.parking_spots.size(), robots);
  ASSERT_EQ(swarm.arrival_times.size(), robots);
  const std::size_t steps = swarm.runs.front().log.scans.size();
  for (std::size_t r = 0; r < robots; ++r) {
    const SimulatedRun& run = swarm.runs[r];
    EXPECT_EQ(swarm.names[r], "robot" + std::to_string(r + 1));
    EXPECT_TRUE(run.log.warnings.empty()) << swarm.names[r];
    ASSERT_EQ(run.log.scans.size(), steps) << swarm.names[r];
    ASSERT_EQ(run.ground_truth.size(), steps) << swarm.names[r];
    for (std::size_t k = 0; k < steps; ++k) {
      ASSERT_EQ(run.log.scans[k].timestamp, static_cast<double>(k) / config.lidar.rate_hz);
      ASSERT_EQ(run.ground_truth[k].first, run.log.scans[k].timestamp);
    }
    // Odometry starts at identity: each robot's frame is its own start pose.
    const Pose2& first_odometry = run.log.scans.front().odometry.value();
    EXPECT_EQ(first_odometry.x, 0.0);
    EXPECT_EQ(first_odometry.y, 0.0);
    EXPECT_EQ(first_odometry.theta, 0.0);
    // Every pose keeps off the walls (sampled: the world's clearance test is slow).
    for (std::size_t k = 0; k < steps; k += 25)
      EXPECT_GE(swarm.world.clearance(run.ground_truth[k].second.translation()), 0.35) << swarm.names[r] << " @" << k;

    // Parked at its spot from its arrival on, scanning with odometry standing still.
    const auto arrival = static_cast<std::size_t>(std::lround(swarm.arrival_times[r] * config.lidar.rate_hz));
    ASSERT_LT(arrival, steps);
    EXPECT_GE(static_cast<double>(steps - 1 - arrival) / config.lidar.rate_hz, 10.0 - 1e-9);
    const Eigen::Vector2d parked = run.ground_truth.back().second.translation();
    EXPECT_LT((parked - swarm.parking_spots[r]).norm(), 0.05) << swarm.names[r];
    EXPECT_TRUE(swarm.rendezvous_area.contains(parked)) << swarm.names[r];
    EXPECT_LT((run.ground_truth[arrival].second.translation() - parked).norm(), 1e-12);
    const Pose2& odometry_at_arrival = run.log.scans[arrival].odometry.value();
    const Pose2& odometry_at_end = run.log.scans.back().odometry.value();
    EXPECT_NEAR(odometry_at_arrival.x, odometry_at_end.x, 1e-9);
    EXPECT_NEAR(odometry_at_arrival.y, odometry_at_end.y, 1e-9);
    EXPECT_NEAR(odometry_at_arrival.theta, odometry_at_end.theta, 1e-9);
  }
  // The last robot arrives, then the robots scan together for a while.
  double last_arrival = 0;
  for (double t : swarm.arrival_times) last_arrival = std::max(last_arrival, t);
  EXPECT_NEAR(swarm.runs.front().ground_truth.back().first - last_arrival, kSwarmWaitAfterLastArrival, 0.2);

  // Starts: pairwise >= 3 m apart, headings not all the same.
  std::set<double> headings;
  for (std::size_t a = 0; a < robots; ++a) {
    headings.insert(heading_at_start(swarm.runs[a]));
    for (std::size_t b = a + 1; b < robots; ++b)
      EXPECT_GE((swarm.runs[a].ground_truth.front().second.translation() -
                 swarm.runs[b].ground_truth.front().second.translation()).norm(),
                3.0)
          << swarm.names[a] << " and " << swarm.names[b];
  }
  if (robots > 1) {
    EXPECT_GT(headings.size(), 1u);
  }
}

// Parked robots are within the sensor's range and see each other, so each
// pair gets an encounter at the end.
void expect_parked_together(const SimulatedSwarm& swarm) {
  const ProximityConfig sensor;
  const std::vector<ProximityEvent> events = proximity_events(swarm.world, swarm, sensor);
  for (std::size_t a = 0; a < swarm.runs.size(); ++a)
    for (std::size_t b = a + 1; b < swarm.runs.size(); ++b) {
      const Eigen::Vector2d pa = swarm.runs[a].ground_truth.back().second.translation();
      const Eigen::Vector2d pb = swarm.runs[b].ground_truth.back().second.translation();
      EXPECT_LE((pa - pb).norm(), sensor.range) << swarm.names[a] << " and " << swarm.names[b];
      EXPECT_TRUE(swarm.world.is_segment_free(pa, pb, 0.05)) << swarm.names[a] << " and " << swarm.names[b];
      const double together = std::max(swarm.arrival_times[a], swarm.arrival_times[b]);
      const bool met_at_the_end = std::any_of(events.begin(), events.end(), [&](const ProximityEvent& e) {
        return e.a == static_cast<int>(a) && e.b == static_cast<int>(b) && e.time > together - sensor.repeat_interval;
      });
      EXPECT_TRUE(met_at_the_end) << swarm.names[a] << " and " << swarm.names[b];
    }
}

TEST(SwarmSim, DefaultThreeRobotsAreWellFormedAndAFewMinutesLong) {
  const SwarmSimConfig config = quick_config(3, 1);
  const SimulatedSwarm swarm = simulate_swarm(config);
  expect_well_formed(config, swarm);
  expect_parked_together(swarm);
  EXPECT_GE(swarm.runs.front().log.scans.size(), 1500u);
  EXPECT_LE(swarm.runs.front().log.scans.size(), 3000u);
  for (const SimulatedRun& run : swarm.runs) {
    EXPECT_NE(run.log.source.find("swarm"), std::string::npos);
    EXPECT_EQ(run.log.scans.front().ranges.size(), 8u);
  }
}

TEST(SwarmSim, SameSeedSameLogs) {
  SwarmSimConfig config = quick_config(3, 4);
  config.lidar.beams = 31;
  const SimulatedSwarm a = simulate_swarm(config);
  const SimulatedSwarm b = simulate_swarm(config);
  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t r = 0; r < a.runs.size(); ++r) {
    ASSERT_EQ(a.runs[r].log.scans.size(), b.runs[r].log.scans.size());
    for (std::size_t k = 0; k < a.runs[r].log.scans.size(); ++k) {
      const LaserScan &sa = a.runs[r].log.scans[k], &sb = b.runs[r].log.scans[k];
      ASSERT_EQ(sa.ranges, sb.ranges) << r << " @" << k;
      ASSERT_EQ(sa.odometry->x, sb.odometry->x);
      ASSERT_EQ(sa.odometry->theta, sb.odometry->theta);
      ASSERT_EQ(a.runs[r].ground_truth[k].second.x, b.runs[r].ground_truth[k].second.x);
      ASSERT_EQ(a.runs[r].ground_truth[k].second.y, b.runs[r].ground_truth[k].second.y);
    }
  }
}

TEST(SwarmSim, SeedsGiveDifferentStartsHeadingsAndRooms) {
  std::set<std::vector<double>> starts;
  std::set<std::vector<std::set<std::size_t>>> room_splits;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const SwarmSimConfig config = quick_config(3, seed);
    const SimulatedSwarm swarm = simulate_swarm(config);
    expect_well_formed(config, swarm);
    std::vector<double> start;
    std::vector<std::set<std::size_t>> rooms;
    for (const SimulatedRun& run : swarm.runs) {
      const Pose2& p = run.ground_truth.front().second;
      start.insert(start.end(), {p.x, p.y, p.theta});
      rooms.push_back(rooms_entered(swarm.world, run));
    }
    starts.insert(start);
    room_splits.insert(rooms);
  }
  EXPECT_EQ(starts.size(), 4u);
  EXPECT_EQ(room_splits.size(), 4u);
}

TEST(SwarmSim, ExploredAreasOverlapButDiffer) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const SimulatedSwarm swarm = simulate_swarm(quick_config(3, seed));
    const std::size_t n_rooms = swarm.world.layout().rooms.size();
    std::vector<int> visitors(n_rooms, 0);
    std::vector<std::set<std::size_t>> entered;
    for (const SimulatedRun& run : swarm.runs) {
      entered.push_back(rooms_entered(swarm.world, run));
      EXPECT_GE(entered.back().size(), 2u) << "seed " << seed;
      EXPECT_LT(entered.back().size(), n_rooms) << "seed " << seed;  // a share, not the whole building
      for (std::size_t k : entered.back()) ++visitors[k];
    }
    // Together they see every room, some rooms twice (maps overlap in rooms,
    // not only in the shared corridor).
    EXPECT_EQ(std::count(visitors.begin(), visitors.end(), 0), 0) << "seed " << seed;
    EXPECT_GT(std::count_if(visitors.begin(), visitors.end(), [](int v) { return v >= 2; }), 0) << "seed " << seed;
    for (std::size_t a = 0; a < entered.size(); ++a)
      for (std::size_t b = a + 1; b < entered.size(); ++b) EXPECT_NE(entered[a], entered[b]) << "seed " << seed;
  }
}

TEST(SwarmSim, RobotsMeetMidRunNotOnlyAtTheEnd) {
  int mid_run = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const SimulatedSwarm swarm = simulate_swarm(quick_config(3, seed));
    int this_seed = 0;
    for (const ProximityEvent& e : proximity_events(swarm.world, swarm, {}))
      if (e.time < std::min(swarm.arrival_times[static_cast<std::size_t>(e.a)],
                            swarm.arrival_times[static_cast<std::size_t>(e.b)]))
        ++this_seed;
    EXPECT_GT(this_seed, 0) << "seed " << seed;
    mid_run += this_seed;
  }
  EXPECT_GE(mid_run, 5);
}

TEST(SwarmSim, EightRobotsInALargerBuilding) {
  const SwarmSimConfig config = quick_config(8, 1);
  EXPECT_GT(config.world.width * config.world.height, WorldConfig{}.width * WorldConfig{}.height);
  const SimulatedSwarm swarm = simulate_swarm(config);
  expect_well_formed(config, swarm);
  expect_parked_together(swarm);
  EXPECT_GE(swarm.world.layout().corridors.size(), 2u);
  EXPECT_GE(swarm.runs.front().log.scans.size(), 1500u);
  EXPECT_LE(swarm.runs.front().log.scans.size(), 4000u);
  // Every corridor is driven by several robots.
  for (std::size_t c = 0; c < swarm.world.layout().corridors.size(); ++c) {
    const Corridor& corridor = swarm.world.layout().corridors[c];
    const Box band = Box{corridor.begin.cwiseMin(corridor.end), corridor.begin.cwiseMax(corridor.end)}.expanded(0.5);
    int drivers = 0;
    for (const SimulatedRun& run : swarm.runs)
      drivers += std::any_of(run.ground_truth.begin(), run.ground_truth.end(),
                             [&](const auto& truth) { return band.contains(truth.second.translation()); });
    EXPECT_GE(drivers, 2) << "corridor " << c;
  }
}

TEST(SwarmSim, WorldConfigScalesWithTheRobotCount) {
  for (int robots = 1; robots <= 64; ++robots) EXPECT_NO_THROW(validate(swarm_world_config(robots))) << robots;
  const WorldConfig three = swarm_world_config(3), eight = swarm_world_config(8);
  EXPECT_EQ(SwarmSimConfig{}.world.width, three.width);
  EXPECT_EQ(SwarmSimConfig{}.world.rooms_x, three.rooms_x);
  EXPECT_EQ(SwarmSimConfig{}.robots, 3);
  EXPECT_GE(three.width * three.height, WorldConfig{}.width * WorldConfig{}.height);
  EXPECT_GT(eight.rooms_x * eight.rooms_y, three.rooms_x * three.rooms_y);
  EXPECT_GE((eight.rooms_y + 1) / 2, 2);  // two corridors
  EXPECT_THROW(swarm_world_config(0), ConfigError);
  EXPECT_THROW(swarm_world_config(65), ConfigError);
}

TEST(SwarmSim, SingleRobotWorks) {
  const SwarmSimConfig config = quick_config(1, 2);
  const SimulatedSwarm swarm = simulate_swarm(config);
  expect_well_formed(config, swarm);
  EXPECT_EQ(rooms_entered(swarm.world, swarm.runs.front()).size(), swarm.world.layout().rooms.size());
}

TEST(SwarmSim, RejectsBadConfigNamingTheField) {
  auto message_of = [](const SwarmSimConfig& config) {
    try {
      simulate_swarm(config);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SwarmSimConfig config = quick_config(3, 1);
  config.robots = 0;
  EXPECT_NE(message_of(config).find("robots"), std::string::npos);
  config.robots = 1000;
  EXPECT_NE(message_of(config).find("robots"), std::string::npos);
  config.robots = 30;  // far too many for the small default building
  EXPECT_NE(message_of(config).find("robots"), std::string::npos);
  config = quick_config(3, 1);
  config.lidar.rate_hz = 0;
  EXPECT_NE(message_of(config).find("rate_hz"), std::string::npos);
  config = quick_config(3, 1);
  config.world.width = -1;
  EXPECT_NE(message_of(config).find("width"), std::string::npos);
}

}  // namespace
}  // namespace dsswarm
