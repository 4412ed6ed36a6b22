#include "sim/world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "common/errors.hpp"
#include "common/rng.hpp"

namespace dsswarm {
namespace {

constexpr double kPi = std::numbers::pi;

// Reference raycast: every segment, no acceleration grid.
double brute_force_raycast(const World& world, const Eigen::Vector2d& o, double angle, double max_range) {
  const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : world.segments()) {
    const Eigen::Vector2d e = s.b - s.a, ao = s.a - o;
    const double denom = d.x() * e.y() - d.y() * e.x();
    if (std::abs(denom) < 1e-12) continue;
    const double t = (ao.x() * e.y() - ao.y() * e.x()) / denom;
    const double u = (ao.x() * d.y() - ao.y() * d.x()) / denom;
    if (t >= 0 && u >= 0 && u <= 1 && t < best) best = t;
  }
  return best <= max_range ? best : std::numeric_limits<double>::infinity();
}

bool same_segments(const World& a, const World& b) {
  if (a.segments().size() != b.segments().size()) return false;
  for (std::size_t i = 0; i < a.segments().size(); ++i)
    if (a.segments()[i].a != b.segments()[i].a || a.segments()[i].b != b.segments()[i].b) return false;
  return true;
}

double tour_length(const std::vector<Eigen::Vector2d>& tour) {
  double length = 0;
  for (std::size_t i = 1; i < tour.size(); ++i) length += (tour[i] - tour[i - 1]).norm();
  return length;
}

TEST(World, RaycastAgainstSingleWall) {
  const World world({Segment{{5, -10}, {5, 10}}});
  EXPECT_NEAR(world.raycast({0, 0}, 0.0, 30), 5.0, 1e-12);
  EXPECT_NEAR(world.raycast({0, 0}, kPi / 4, 30), 5.0 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(world.raycast({1, 3}, 0.0, 30), 4.0, 1e-12);
  EXPECT_TRUE(std::isinf(world.raycast({0, 0}, kPi, 30)));         // facing away
  EXPECT_TRUE(std::isinf(world.raycast({0, 0}, kPi / 2, 30)));     // parallel
  EXPECT_TRUE(std::isinf(world.raycast({0, 0}, 0.0, 4.9)));        // beyond max range
  EXPECT_TRUE(std::isinf(world.raycast({0, 0}, 1.2, 30)));         // passes above the wall's end
  EXPECT_NEAR(world.raycast({10, 0}, kPi, 30), 5.0, 1e-12);        // from the other side
  EXPECT_TRUE(std::isinf(world.raycast({0, 50}, 0.0, 30)));        // outside the grid, misses
  EXPECT_NEAR(world.raycast({-40, 0}, 0.0, 100), 45.0, 1e-9);      // enters the grid from far away
}

TEST(World, RaycastReturnsNearestOfSeveralWalls) {
  const World world({Segment{{5, -10}, {5, 10}}, Segment{{3, -1}, {3, 1}}, Segment{{8, -10}, {8, 10}}});
  EXPECT_NEAR(world.raycast({0, 0}, 0.0, 30), 3.0, 1e-12);
  EXPECT_NEAR(world.raycast({0, 2}, 0.0, 30), 5.0, 1e-12);
  EXPECT_NEAR(world.raycast({6, 0}, 0.0, 30), 2.0, 1e-12);
}

TEST(World, GridRaycastMatchesBruteForce) {
  const World world = generate_world({});
  Rng rng(5);
  const Box b = world.bounds();
  for (int i = 0; i < 4000; ++i) {
    // Origins also outside the building, so rays enter the grid from outside.
    const Eigen::Vector2d o(rng.uniform(b.min.x() - 5, b.max.x() + 5), rng.uniform(b.min.y() - 5, b.max.y() + 5));
    const double angle = rng.uniform(-kPi, kPi);
    const double max_range = rng.uniform(1.0, 40.0);
    const double fast = world.raycast(o, angle, max_range);
    const double slow = brute_force_raycast(world, o, angle, max_range);
    if (std::isinf(slow)) {
      EXPECT_TRUE(std::isinf(fast)) << "ray " << i;
    } else {
      EXPECT_NEAR(fast, slow, 1e-9) << "ray " << i;
    }
  }
}

TEST(World, ClearanceAndFreeSpace) {
  const World world({Segment{{0, 0}, {10, 0}}}, {Box{{2, 2}, {4, 4}}});
  EXPECT_NEAR(world.clearance({5, 1}), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(world.clearance({3, 3}), 0.0);  // inside the solid box
  EXPECT_NEAR(world.clearance({3, 5}), 1.0, 1e-12);
  EXPECT_TRUE(world.is_free({5, 1}, 0.4));
  EXPECT_FALSE(world.is_free({5, 0.3}, 0.4));
  EXPECT_FALSE(world.is_free({3, 3}, 0.4));
  EXPECT_TRUE(world.is_segment_free({0, 1}, {10, 1}, 0.5));
  EXPECT_FALSE(world.is_segment_free({3, 1}, {3, 6}, 0.1));     // crosses the box
  EXPECT_FALSE(world.is_segment_free({5, 1}, {5, -1}, 0.1));    // crosses the wall
  EXPECT_FALSE(world.is_segment_free({1, 1.5}, {5, 1.5}, 0.6)); // grazes the box corner
}

TEST(World, GenerationIsDeterministicInTheSeed) {
  WorldConfig config;
  const World a = generate_world(config);
  const World b = generate_world(config);
  EXPECT_TRUE(same_segments(a, b));
  config.seed = 2;
  const World c = generate_world(config);
  EXPECT_FALSE(same_segments(a, c));
}

TEST(World, DefaultBuildingHasRoomsCorridorAndClutter) {
  const WorldConfig config;
  const World world = generate_world(config);
  const auto& layout = world.layout();
  ASSERT_EQ(layout.rooms.size(), 8u);
  ASSERT_EQ(layout.corridors.size(), 1u);
  EXPECT_NEAR(world.bounds().min.x(), -config.wall_thickness / 2, 1e-12);
  EXPECT_NEAR(world.bounds().max.y(), config.height + config.wall_thickness / 2, 1e-12);
  // 4 outer walls, 2 door walls per room, 3 dividers per row, clutter.
  const std::size_t walls = 4 + 2 * 8 + 3 * 2;
  EXPECT_GT(world.solids().size(), walls);
  EXPECT_LE(world.solids().size(), walls + 8 * static_cast<std::size_t>(config.clutter_per_room));
  for (const Room& room : layout.rooms) {
    // The doorway is open: from the corridor a beam through the door centre goes into the room.
    const Eigen::Vector2d in_corridor = room.door - 0.9 * room.into_room;
    const double beam_angle = std::atan2(room.into_room.y(), room.into_room.x());
    EXPECT_GT(world.raycast(in_corridor, beam_angle, 30), 2.0);
    // ... and a beam beside the door hits the wall.
    const Eigen::Vector2d beside = in_corridor + Eigen::Vector2d(-room.into_room.y(), room.into_room.x()) * 0.8;
    EXPECT_LT(world.raycast(beside, beam_angle, 30), 1.0);
    EXPECT_TRUE(world.is_segment_free(room.inside_door, room.safe_spot, 0.6));
  }
  const Corridor& corridor = layout.corridors.front();
  EXPECT_TRUE(world.is_segment_free(corridor.begin, corridor.end, 0.9));
}

TEST(World, RejectsUnusableConfigs) {
  auto generate_with = [](auto change) {
    WorldConfig c;
    change(c);
    return generate_world(c);
  };
  EXPECT_THROW(generate_with([](WorldConfig& c) { c.door_width = 0.5; }), ConfigError);
  EXPECT_THROW(generate_with([](WorldConfig& c) { c.rooms_x = 0; }), ConfigError);
  EXPECT_THROW(generate_with([](WorldConfig& c) { c.rooms_x = 20; }), ConfigError);  // 1.5 m rooms
  EXPECT_THROW(generate_with([](WorldConfig& c) { c.height = std::nan(""); }), ConfigError);
  EXPECT_THROW(generate_with([](WorldConfig& c) { c.corridor_width = 0.5; }), ConfigError);
  EXPECT_THROW(generate_with([](WorldConfig& c) { c.clutter_per_room = -1; }), ConfigError);
}

// The tour must be drivable: every leg, checked point by point (independently
// of is_segment_free), keeps 0.45 m from every wall.
void expect_tour_clear(const World& world, const std::vector<Eigen::Vector2d>& tour) {
  ASSERT_GE(tour.size(), 2u);
  double worst = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < tour.size(); ++i) {
    const double length = (tour[i] - tour[i - 1]).norm();
    const int steps = static_cast<int>(std::ceil(length / 0.02));
    for (int k = 0; k <= steps; ++k) worst = std::min(worst, world.clearance(tour[i - 1] + (tour[i] - tour[i - 1]) * k / steps));
  }
  EXPECT_GE(worst, 0.45);
}

TEST(WaypointTour, KeepsClearanceInManyBuildings) {
  for (std::uint64_t world_seed = 1; world_seed <= 4; ++world_seed) {
    WorldConfig config;
    config.seed = world_seed;
    config.clutter_per_room = 6;  // crowded rooms: the tour must still find its way
    const World world = generate_world(config);
    for (std::uint64_t tour_seed = 1; tour_seed <= 3; ++tour_seed) {
      SCOPED_TRACE(testing::Message() << "world " << world_seed << " tour " << tour_seed);
      expect_tour_clear(world, world.waypoint_tour(tour_seed));
    }
  }
}

TEST(WaypointTour, SeveralCorridorsAreJoinedBySpine) {
  WorldConfig config;
  config.rooms_y = 3;  // two corridors
  config.height = 30;
  const World world = generate_world(config);
  ASSERT_EQ(world.layout().corridors.size(), 2u);
  const auto tour = world.waypoint_tour(3);
  expect_tour_clear(world, tour);
  // Every room's doorway is passed.
  for (const Room& room : world.layout().rooms) {
    bool entered = false;
    for (const auto& p : tour) entered = entered || (p - room.inside_door).norm() < 1e-9;
    EXPECT_TRUE(entered);
  }
}

TEST(WaypointTour, VisitsEveryRoomAndLoopsBack) {
  const World world = generate_world({});
  const auto tour = world.waypoint_tour(7);
  for (const Room& room : world.layout().rooms) {
    bool inside = false;
    for (const auto& p : tour) inside = inside || room.area.expanded(-0.5).contains(p);
    EXPECT_TRUE(inside);
  }
  // Loop: after at least 30 m of driving the tour comes back within 1 m of an earlier waypoint.
  bool loops_back = false;
  double travelled = 0;
  std::vector<double> at(tour.size(), 0.0);
  for (std::size_t i = 1; i < tour.size(); ++i) at[i] = (travelled += (tour[i] - tour[i - 1]).norm());
  for (std::size_t j = 0; j < tour.size(); ++j)
    for (std::size_t i = 0; i < j; ++i)
      loops_back = loops_back || (at[j] - at[i] > 30.0 && (tour[j] - tour[i]).norm() < 1.0);
  EXPECT_TRUE(loops_back);
  EXPECT_GT(tour_length(tour), 80.0);
  EXPECT_LT(tour_length(tour), 150.0);
}

TEST(WaypointTour, DeterministicInTheSeed) {
  const World world = generate_world({});
  EXPECT_EQ(world.waypoint_tour(3), world.waypoint_tour(3));
  EXPECT_NE(world.waypoint_tour(3), world.waypoint_tour(4));
  EXPECT_TRUE(World({Segment{{0, 0}, {1, 0}}}).waypoint_tour(1).empty());  // no rooms, no tour
}

}  // namespace
}  // namespace dsswarm
