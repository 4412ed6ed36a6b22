#include "swarm/relative_pose.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "swarm/encounter.hpp"
#include "swarm/test_scenes.hpp"

namespace dsswarm {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Robot A mapped the room from a few poses (its frame at a_frame) and stands at a_pose.
struct MappedOffice {
  World world = test::l_shaped_office();
  Pose2 a_frame{1.0, 1.0, 0.3};
  Rng rng{11};  // goes on drawing the other robot's scans
  MultiResMap map =
      test::map_from(world, {{2.0, 1.5, 0.3}, {3.0, 2.5, 1.0}, {5.5, 2.0, 0.0}, {2.0, 5.0, 1.6}}, a_frame, rng);
  Pose2 a_pose = a_frame.inverse() * Pose2{3.0, 2.5, 1.0};
};

// Robot B, somewhere within 3 m of robot A and facing anywhere, takes one scan.
TEST(RelativePose, RecoversThePoseOfAScanWithAnyHeading) {
  MappedOffice o;
  for (int trial = 0; trial < 6; ++trial) {
    Pose2 b_world;
    do {
      b_world = {o.rng.uniform(0.6, 6.0), o.rng.uniform(0.6, 3.4),
                 o.rng.uniform(-std::numbers::pi, std::numbers::pi)};
    } while (!o.world.is_free(b_world.translation(), 0.3));
    const Pose2 truth = o.a_frame.inverse() * b_world;
    if ((truth.translation() - o.a_pose.translation()).norm() > 3.0) continue;
    const RelativePoseResult r = locate_scan(o.map, test::scan_at(o.world, b_world, o.rng), o.a_pose.translation(),
                                             RelativePoseConfig{}, 1 + trial);
    EXPECT_NEAR(r.best.pose.x, truth.x, 0.05) << "trial " << trial;
    EXPECT_NEAR(r.best.pose.y, truth.y, 0.05) << "trial " << trial;
    EXPECT_NEAR(normalize_angle(r.best.pose.theta - truth.theta), 0.0, 1.0 * kDeg) << "trial " << trial;
    EXPECT_GT(r.best.inlier_ratio, 0.8);
  }
}

// A point far beyond the map (a log's bogus range, say) reads as unknown and
// costs nothing: the search's dense copy of the map stops at the map's edge.
TEST(RelativePose, AFarPointInTheScanNeitherCostsMemoryNorMovesThePlacement) {
  MappedOffice o;
  const Pose2 b_world{3.5, 2.0, 2.0};
  const Pose2 truth = o.a_frame.inverse() * b_world;
  std::vector<ScanPoint> points = test::scan_at(o.world, b_world, o.rng);
  points.insert(points.begin(), ScanPoint{5.0e4f, -5.0e4f, 1.0f});  // the exhaustive search's subset starts here
  const RelativePoseResult r = locate_scan(o.map, points, o.a_pose.translation(), RelativePoseConfig{}, 3);
  EXPECT_NEAR(r.best.pose.x, truth.x, 0.05);
  EXPECT_NEAR(r.best.pose.y, truth.y, 0.05);
  EXPECT_NEAR(normalize_angle(r.best.pose.theta - truth.theta), 0.0, 1.0 * kDeg);
}

struct TwoRobots {
  MultiResMap map_a, map_b;
  EncounterView a, b;
  Pose2 b_frame_in_a;  // truth
};

// Two robots that each mapped from their own start, now at a_world and b_world.
TwoRobots meet(const World& world, const Pose2& a_start, const Pose2& b_start, const Pose2& a_world,
               const Pose2& b_world, Rng& rng) {
  TwoRobots t;
  // Each drove from its start to where it is now, scanning on the way.
  auto drive = [](const Pose2& from, const Pose2& to) {
    std::vector<Pose2> path;
    for (int k = 0; k <= 10; ++k) path.push_back(interpolate(from, to, k / 10.0));
    return path;
  };
  t.map_a = test::map_from(world, drive(a_start, a_world), a_start, rng);
  t.map_b = test::map_from(world, drive(b_start, b_world), b_start, rng);
  t.a = {&t.map_a, test::scan_at(world, a_world, rng), a_start.inverse() * a_world, {}, {}, 0};
  t.a.surroundings = surroundings_points(t.map_a, t.a.pose, 8.0, 2000);
  t.b = {&t.map_b, test::scan_at(world, b_world, rng), b_start.inverse() * b_world, {}, {}, 0};
  t.b.surroundings = surroundings_points(t.map_b, t.b.pose, 8.0, 2000);
  t.a.wide_surroundings = surroundings_points(t.map_a, t.a.pose, 40.0, 8000);
  t.b.wide_surroundings = surroundings_points(t.map_b, t.b.pose, 40.0, 8000);
  t.b_frame_in_a = a_start.inverse() * b_start;
  return t;
}

// The scene most tests share: two robots that started across the L-shaped
// office meet in its long arm, 2 m apart, facing each other.
const Pose2 kOfficeAStart{1.5, 1.5, 0.4}, kOfficeAWorld{3.0, 2.0, 0.1};
TwoRobots meet_in_the_office(std::uint64_t seed) {
  Rng rng(seed);
  return meet(test::l_shaped_office(), kOfficeAStart, {8.5, 2.0, -2.5}, kOfficeAWorld, {5.0, 2.5, 2.9}, rng);
}

TEST(Encounter, AcceptsAndRecoversTheTransformBetweenFrames) {
  TwoRobots t = meet_in_the_office(2);
  const EncounterEstimate e = estimate_encounter(t.a, t.b, EncounterConfig{}, 5);
  ASSERT_TRUE(e.accepted) << e.reason;
  EXPECT_NEAR(e.b_frame_in_a.x, t.b_frame_in_a.x, 0.05);
  EXPECT_NEAR(e.b_frame_in_a.y, t.b_frame_in_a.y, 0.05);
  EXPECT_NEAR(normalize_angle(e.b_frame_in_a.theta - t.b_frame_in_a.theta), 0.0, 0.5 * kDeg);
  EXPECT_LT(e.disagreement_xy, 0.1);
}

TEST(RelativePose, RefinePlacementPullsAnOffsetPlacementOntoTheMap) {
  TwoRobots t = meet_in_the_office(3);
  const Pose2 truth = t.b_frame_in_a * t.b.pose;  // B's base pose in A's map
  const Pose2 start = truth * Pose2(0.04, -0.03, 0.6 * kDeg);
  const MatchResult m = refine_placement(t.map_a, t.b.points, t.b.wide_surroundings, start, RelativePoseConfig{}, 9);
  const Pose2 d = between(truth, m.pose);
  EXPECT_LT(std::hypot(d.x, d.y), 0.015);
  EXPECT_LT(std::abs(d.theta), 0.15 * kDeg);
  EXPECT_GT(m.evaluations, 0);
}

TEST(Encounter, TheMergeTransformIsRefinedAgainstTheWideSurroundings) {
  TwoRobots t = meet_in_the_office(2);
  auto error_at_b = [&](const Pose2& transform) {
    const Pose2 d = between(t.b_frame_in_a * t.b.pose, transform * t.b.pose);
    return std::hypot(d.x, d.y) + std::abs(d.theta);  // metres + radians: both small here
  };
  const EncounterEstimate wide = estimate_encounter(t.a, t.b, EncounterConfig{}, 5);
  ASSERT_TRUE(wide.accepted) << wide.reason;
  EXPECT_LE(error_at_b(wide.b_frame_in_a), error_at_b(wide.b_frame_in_a_near) + 0.005);
  EXPECT_LT(error_at_b(wide.b_frame_in_a), 0.03);
  // Without wide surroundings the near estimate is the answer.
  t.a.wide_surroundings.clear();
  const EncounterEstimate near = estimate_encounter(t.a, t.b, EncounterConfig{}, 5);
  ASSERT_TRUE(near.accepted) << near.reason;
  EXPECT_EQ(near.b_frame_in_a.x, near.b_frame_in_a_near.x);
  EXPECT_EQ(near.b_frame_in_a.theta, near.b_frame_in_a_near.theta);
}

TEST(Encounter, KeepsTheMeetingPointEstimateOrRejectsWhenTheMapsAsWholesDisagree) {
  TwoRobots t = meet_in_the_office(2);
  const EncounterEstimate straight = estimate_encounter(t.a, t.b, EncounterConfig{}, 5);
  ASSERT_TRUE(straight.accepted) << straight.reason;
  EXPECT_LT(straight.wide_moved_xy, 0.03);
  // B's map bent: everything it knows, seen from where it stands, turned by
  // 4° and shifted 10 cm, while its current scan is straight.
  const Pose2 bend{0.1, 0.0, 4.0 * kDeg};
  for (ScanPoint& p : t.b.wide_surroundings) {
    const Eigen::Vector2d q = bend * Eigen::Vector2d(p.x, p.y);
    p.x = static_cast<float>(q.x());
    p.y = static_cast<float>(q.y());
  }
  // By default the estimate where the robots met stands.
  const EncounterEstimate kept = estimate_encounter(t.a, t.b, EncounterConfig{}, 5);
  ASSERT_TRUE(kept.accepted) << kept.reason;
  EXPECT_GT(std::max(kept.wide_moved_xy / EncounterConfig{}.agree_xy, kept.wide_moved_theta / EncounterConfig{}.agree_theta),
            1.0);
  EXPECT_EQ(kept.b_frame_in_a.x, kept.b_frame_in_a_near.x);
  EXPECT_EQ(kept.b_frame_in_a.theta, kept.b_frame_in_a_near.theta);
  // With reject_bent_maps the pair waits for a better encounter.
  EncounterConfig strict;
  strict.reject_bent_maps = true;
  const EncounterEstimate bent = estimate_encounter(t.a, t.b, strict, 5);
  EXPECT_FALSE(bent.accepted);
  EXPECT_NE(bent.reason.find("maps disagree"), std::string::npos) << bent.reason;
}

TEST(Encounter, RejectsALongFeaturelessCorridor) {
  // 2 m wide, far longer than the lidar reaches: every position along it fits.
  const World world({{{-200, 0}, {200, 0}}, {{-200, 2}, {200, 2}}});
  Rng rng(4);
  TwoRobots t = meet(world, {0.0, 1.0, 0.0}, {2.0, 1.0, 3.0}, {0.5, 1.0, 0.0}, {2.0, 1.0, 3.0}, rng);
  const EncounterEstimate e = estimate_encounter(t.a, t.b, EncounterConfig{}, 5);
  EXPECT_FALSE(e.accepted);
  EXPECT_NE(e.reason.find("ambiguous"), std::string::npos) << e.reason;
}

TEST(Encounter, RejectsASymmetricRoom) {
  // An empty 6 × 4 m room looks the same turned by 180°.
  const World world({{{0, 0}, {6, 0}}, {{6, 0}, {6, 4}}, {{6, 4}, {0, 4}}, {{0, 4}, {0, 0}}});
  Rng rng(6);
  TwoRobots t = meet(world, {2.0, 2.0, 0.0}, {4.0, 2.0, 1.0}, {2.0, 2.0, 0.0}, {4.0, 2.0, 1.0}, rng);
  const EncounterEstimate e = estimate_encounter(t.a, t.b, EncounterConfig{}, 5);
  EXPECT_FALSE(e.accepted);
  EXPECT_NE(e.reason.find("ambiguous"), std::string::npos) << e.reason;
}

TEST(Encounter, RejectsWhenTheOtherRobotSeesUnmappedSpace) {
  TwoRobots t = meet_in_the_office(8);
  const MultiResMap empty;
  t.a.map = &empty;
  EXPECT_FALSE(estimate_encounter(t.a, t.b, EncounterConfig{}, 5).accepted);
}

// Robot A came back to where it meets B before closing its loop: its
// composed map holds an earlier visit of the same ground, 0.25 m / 4° out of
// line and seen twice as often, while its recent submaps hold what it sees
// now. The peer is placed in both, and the recent placement kept.
TEST(Encounter, APeerIsPlacedInTheRecentSubmapsWhereTheComposedMapIsOutOfLine) {
  TwoRobots t = meet_in_the_office(2);
  const World world = test::l_shaped_office();
  const Pose2 a_start = kOfficeAStart, a_world = kOfficeAWorld;
  const Pose2 out_of_line{0.25, -0.1, 4.0 * kDeg};
  Rng rng(21);
  MultiResMap composed = t.map_a;
  for (int visit = 0; visit < 2; ++visit)
    for (int k = 0; k <= 10; ++k) {
      const Pose2 p = interpolate(a_start, a_world, k / 10.0);
      composed.insert_scan(out_of_line * (a_start.inverse() * p), Pose2{}, test::scan_at(world, p, rng));
    }
  const Pose2 truth = t.b_frame_in_a * t.b.pose;  // B's base in A's frame
  auto error_of = [&](const PeerPlacement& placed) {
    const Pose2 d = between(truth, placed.located.best.pose);
    return std::hypot(d.x, d.y) + std::abs(d.theta);  // metres + radians: both small here
  };
  t.a.map = &composed;
  const PeerPlacement in_composed = locate_peer(t.a, t.b, EncounterConfig{}, 5);
  t.a.recent_map = std::make_shared<const MultiResMap>(t.map_a);
  const PeerPlacement in_both = locate_peer(t.a, t.b, EncounterConfig{}, 5);
  EXPECT_GT(error_of(in_composed), 0.05);
  EXPECT_LT(error_of(in_both), 0.02);
  // Where the composed map is in line, it fits better and is kept.
  t.a.map = &t.map_a;
  MultiResMap less_of_it;
  for (int k = 8; k <= 10; ++k) {
    const Pose2 p = interpolate(a_start, a_world, k / 10.0);
    less_of_it.insert_scan(a_start.inverse() * p, Pose2{}, test::scan_at(world, p, rng));
  }
  t.a.recent_map = std::make_shared<const MultiResMap>(std::move(less_of_it));
  const PeerPlacement whole = locate_peer(t.a, t.b, EncounterConfig{}, 5);
  t.a.recent_map = nullptr;
  EXPECT_EQ(whole.located.best.pose.x, locate_peer(t.a, t.b, EncounterConfig{}, 5).located.best.pose.x);
}

// The same-side check, at the true placement and across a thin wall. In a
// corridor most hits meet their wall at a grazing angle; 15 cm back along
// such a beam is still inside the wall's own cells, so the check steps back
// until it is clear of them (or leaves the hit out).
TEST(SameSideRatio, HighAtTheTruePlacementInACorridor) {
  const World corridor({{{-12, -1}, {12, -1}}, {{-12, 1}, {12, 1}}, {{-12, -1}, {-12, 1}}, {{12, -1}, {12, 1}}});
  Rng rng(5);
  const MultiResMap map = test::map_from(corridor, {{-4.0, 0.0, 0.0}, {-2.0, 0.1, 0.0}, {0.0, -0.1, 0.0},
                                                    {2.0, 0.0, 0.0}, {4.0, 0.1, 0.0}}, Pose2{}, rng);
  for (const Pose2 b : {Pose2{1.0, 0.3, 0.2}, Pose2{-3.0, -0.4, 2.5}, Pose2{3.3, 0.0, -1.2}})
    EXPECT_GT(same_side_ratio(map.finest(), test::scan_at(corridor, b, rng), b), 0.9) << b.x;
}

TEST(SameSideRatio, LowForAScanThatMeetsAThinWallFromTheOtherSide) {
  // A thin wall at y = 0 splits a room; A has only been in the upper half.
  const World room({{{-5, -3}, {5, -3}}, {{5, -3}, {5, 3}}, {{5, 3}, {-5, 3}}, {{-5, 3}, {-5, -3}}, {{-5, 0}, {5, 0}}});
  Rng rng(6);
  const MultiResMap map =
      test::map_from(room, {{-2.0, 1.5, 0.0}, {0.0, 1.5, 1.0}, {2.0, 1.5, 2.0}}, Pose2{}, rng);
  // B stands below the wall; its hits on the wall land on A's wall cells.
  for (const Pose2 b : {Pose2{0.0, -1.5, 0.0}, Pose2{-1.0, -0.8, 1.0}, Pose2{2.5, -2.0, -2.0}})
    EXPECT_LT(same_side_ratio(map.finest(), test::scan_at(room, b, rng), b), 0.2) << b.x;
  // The same place seen from above passes.
  const Pose2 above{1.0, 0.8, 0.5};
  EXPECT_GT(same_side_ratio(map.finest(), test::scan_at(room, above, rng), above), 0.9);
}

// The thin-wall room again: A has been in the upper half only. B's scan,
// turned half a circle about a point of the wall, lands below it: its wall
// hits on A's wall cells, met from behind. Surroundings made to fit that
// placement perfectly (as a robot's own obstacles can, far from where the
// two robots' views of a place agree) must not win over a placement that
// can be.
TEST(RelativePose, APlacementThatMeetsWallsFromBehindRanksAfterOneThatCanBe) {
  const World room({{{-5, -3}, {5, -3}}, {{5, -3}, {5, 3}}, {{5, 3}, {-5, 3}}, {{-5, 3}, {-5, -3}}, {{-5, 0}, {5, 0}}});
  Rng rng(7);
  const MultiResMap map = test::map_from(room, {{-2.0, 1.5, 0.0}, {0.0, 1.5, 1.0}, {2.0, 1.5, 2.0}}, Pose2{}, rng);
  const Pose2 truth{1.0, 0.8, 0.5};
  const Pose2 behind = Pose2{1.0, 0.0, std::numbers::pi} * Pose2{0.0, 0.8, 0.5};  // truth turned about (1, 0)
  const std::vector<ScanPoint> scan = test::scan_at(room, truth, rng);
  const std::vector<ScanPoint> fits_behind = surroundings_points(map, behind, 8.0, 2000);
  RelativePoseConfig by_surroundings;
  by_surroundings.possible_same_side = 0.0;
  const RelativePoseResult old = locate_scan(map, scan, {1.0, 0.0}, by_surroundings, 3, fits_behind);
  ASSERT_LT(old.best.same_side_ratio, 0.5) << "the premise: ranked by the surroundings alone, it lands behind the wall";
  const RelativePoseResult r = locate_scan(map, scan, {1.0, 0.0}, RelativePoseConfig{}, 3, fits_behind);
  // Above the wall: the truth or its turn about the half room's centre (a
  // symmetric box; the runner-up check is what turns such a pair down).
  EXPECT_GT(r.best.same_side_ratio, 0.8);
  EXPECT_GT(r.best.pose.y, 0.3);
  ASSERT_TRUE(r.runner_up);
  EXPECT_GT(r.runner_up->same_side_ratio, 0.8) << "an impossible placement is no rival to a possible one";
}

// A lattice too fine for memory is a configuration error naming its fields,
// not an allocation that brings the robot down.
TEST(RelativePose, ALatticeTooFineForMemoryIsAConfigError) {
  RelativePoseConfig config;
  EXPECT_NO_THROW(config.validate());
  config.search_radius = 50.0;
  config.coarse_step_xy = 0.01;
  try {
    config.validate();
    FAIL() << "a lattice of ~10^6 M poses was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("encounter.search_radius"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("coarse_step_xy"), std::string::npos) << e.what();
  }
  config.search_radius = 10.0;
  config.coarse_step_xy = 0.1;  // 31 400 positions x 120 headings: 3.8 M
  EXPECT_NO_THROW(config.validate());
}

}  // namespace
}  // namespace dsswarm
