#include "sim/proximity.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

using Trajectory = std::function<Eigen::Vector2d(double t)>;
constexpr double kRate = 10.0;

// Hand-made robots on one 10 Hz clock (ground truth only; the sensor needs nothing else).
SimulatedSwarm make_swarm(const World& world, const std::vector<Trajectory>& robots, double duration) {
  SimulatedSwarm swarm{world, {}, {}, {}, {}, {}};
  const auto steps = static_cast<std::size_t>(std::lround(duration * kRate)) + 1;
  for (std::size_t r = 0; r < robots.size(); ++r) {
    swarm.names.push_back("robot" + std::to_string(r + 1));
    SimulatedRun run;
    for (std::size_t k = 0; k < steps; ++k) {
      const double t = static_cast<double>(k) / kRate;
      const Eigen::Vector2d p = robots[r](t);
      run.ground_truth.emplace_back(t, Pose2(p.x(), p.y(), 0.0));
    }
    swarm.runs.push_back(std::move(run));
  }
  return swarm;
}

Trajectory at(double x, double y) {
  return [=](double) { return Eigen::Vector2d(x, y); };
}

void expect_events(const std::vector<ProximityEvent>& actual, const std::vector<ProximityEvent>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    EXPECT_NEAR(actual[i].time, expected[i].time, 1e-9) << "event " << i;
    EXPECT_EQ(actual[i].a, expected[i].a) << "event " << i;
    EXPECT_EQ(actual[i].b, expected[i].b) << "event " << i;
  }
}

const World kOpenSpace{std::vector<Segment>{}};

TEST(Proximity, FiresOnEnteringRangeAndRepeatsWhileNear) {
  // Robot 2 approaches at 0.5 m/s and is within 3 m from t = 14.04 on
  // (the first scan: 14.1), then stays 2 m away until t = 50.
  const auto approach = [](double t) { return Eigen::Vector2d(std::max(2.0, 10.02 - 0.5 * t), 0.0); };
  const SimulatedSwarm swarm = make_swarm(kOpenSpace, {at(0, 0), approach}, 50.0);
  expect_events(proximity_events(kOpenSpace, swarm, {}), {{14.1, 0, 1}, {29.1, 0, 1}, {44.1, 0, 1}});

  ProximityConfig once;
  once.repeat_interval = std::numeric_limits<double>::infinity();
  expect_events(proximity_events(kOpenSpace, swarm, once), {{14.1, 0, 1}});
  ProximityConfig wide;
  wide.range = 8.0;  // within 8 m from t = 4.04
  expect_events(proximity_events(kOpenSpace, swarm, wide), {{4.1, 0, 1}, {19.1, 0, 1}, {34.1, 0, 1}, {49.1, 0, 1}});
}

TEST(Proximity, NoEventsWhileFarApart) {
  const SimulatedSwarm swarm = make_swarm(kOpenSpace, {at(0, 0), at(3.01, 0), at(-3.5, 0)}, 30.0);
  EXPECT_TRUE(proximity_events(kOpenSpace, swarm, {}).empty());
}

TEST(Proximity, WallBlocksLineOfSight) {
  // A wall 2 m long halfway between robot 1 and robot 2's line; robot 2 walks
  // past at 1 m/s. It is within 3 m for |y| <= 2.236 but hidden behind the
  // wall for |y| up to about 2.1: seen briefly on both sides.
  const World wall({Segment{{1, -1}, {1, 1}}});
  const auto walk = [](double t) { return Eigen::Vector2d(2.0, -10.0 + t); };
  const SimulatedSwarm swarm = make_swarm(wall, {at(0, 0), walk}, 20.0);
  expect_events(proximity_events(wall, swarm, {}), {{7.8, 0, 1}, {12.2, 0, 1}});

  ProximityConfig no_sight;
  no_sight.line_of_sight = false;  // one long encounter, shorter than the repeat interval
  expect_events(proximity_events(wall, swarm, no_sight), {{7.8, 0, 1}});

  // Robots on both sides of a long wall never see each other.
  const World long_wall({Segment{{1, -50}, {1, 50}}});
  const SimulatedSwarm hidden = make_swarm(long_wall, {at(0, 0), at(2, 0)}, 40.0);
  EXPECT_TRUE(proximity_events(long_wall, hidden, {}).empty());
  expect_events(proximity_events(long_wall, hidden, no_sight), {{0.0, 0, 1}, {15.0, 0, 1}, {30.0, 0, 1}});
}

TEST(Proximity, LeavingAndComingBackFiresAtOnce) {
  // Near, away for one second (t in [5, 6)), near again: no waiting for the interval.
  const auto away_and_back = [](double t) {
    return Eigen::Vector2d(t >= 5.0 - 1e-9 && t < 6.0 - 1e-9 ? 5.0 : 2.0, 0.0);
  };
  const SimulatedSwarm swarm = make_swarm(kOpenSpace, {at(0, 0), away_and_back}, 25.0);
  expect_events(proximity_events(kOpenSpace, swarm, {}), {{0.0, 0, 1}, {6.0, 0, 1}, {21.0, 0, 1}});
}

TEST(Proximity, EventsSortedByTimeThenPair) {
  // Robots 1 and 3 meet first; then everyone is together.
  const auto late = [](double t) { return Eigen::Vector2d(t < 2.0 - 1e-9 ? 20.0 : 1.0, 1.0); };
  const SimulatedSwarm swarm = make_swarm(kOpenSpace, {at(0, 0), late, at(1, 0)}, 16.0);
  expect_events(proximity_events(kOpenSpace, swarm, {}),
                {{0.0, 0, 2}, {2.0, 0, 1}, {2.0, 1, 2}, {15.0, 0, 2}});
  // A single robot or an empty swarm: nobody to meet.
  EXPECT_TRUE(proximity_events(kOpenSpace, make_swarm(kOpenSpace, {at(0, 0)}, 5.0), {}).empty());
  EXPECT_TRUE(proximity_events(kOpenSpace, make_swarm(kOpenSpace, {}, 5.0), {}).empty());
}

TEST(Proximity, RejectsBadConfigNamingTheField) {
  const SimulatedSwarm swarm = make_swarm(kOpenSpace, {at(0, 0), at(1, 0)}, 1.0);
  auto message_of = [&](const ProximityConfig& config) {
    try {
      proximity_events(kOpenSpace, swarm, config);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  ProximityConfig c;
  c.range = 0;
  EXPECT_NE(message_of(c).find("range"), std::string::npos);
  c.range = std::nan("");
  EXPECT_NE(message_of(c).find("range"), std::string::npos);
  c.range = std::numeric_limits<double>::infinity();
  EXPECT_NE(message_of(c).find("range"), std::string::npos);
  c = {};
  c.repeat_interval = 0;
  EXPECT_NE(message_of(c).find("repeat_interval"), std::string::npos);
  c.repeat_interval = -5;
  EXPECT_NE(message_of(c).find("repeat_interval"), std::string::npos);
  c.repeat_interval = std::nan("");
  EXPECT_NE(message_of(c).find("repeat_interval"), std::string::npos);
}

TEST(Proximity, RejectsRobotsNotOnOneClock) {
  SimulatedSwarm shorter = make_swarm(kOpenSpace, {at(0, 0), at(1, 0)}, 2.0);
  shorter.runs[1].ground_truth.pop_back();
  EXPECT_THROW(proximity_events(kOpenSpace, shorter, {}), InputError);

  SimulatedSwarm shifted = make_swarm(kOpenSpace, {at(0, 0), at(1, 0)}, 2.0);
  for (auto& [time, pose] : shifted.runs[1].ground_truth) time += 0.05;
  try {
    proximity_events(kOpenSpace, shifted, {});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("robot2"), std::string::npos) << e.what();
  }

  SimulatedSwarm broken = make_swarm(kOpenSpace, {at(0, 0), at(1, 0)}, 2.0);
  broken.runs[0].ground_truth[3].second.x = std::nan("");
  EXPECT_THROW(proximity_events(kOpenSpace, broken, {}), InputError);
}

}  // namespace
}  // namespace dsswarm
