#include "swarm/map_merge.hpp"

#include <gtest/gtest.h>

#include <random>

#include "common/errors.hpp"
#include "grid/sampling.hpp"
#include "matching/scan_scorer.hpp"
#include "swarm/map_knowledge.hpp"
#include "swarm/test_scenes.hpp"

namespace dsswarm {
namespace {

bool same_cells(const DsGrid& a, const DsGrid& b) {
  bool same = a.tiles_allocated() == b.tiles_allocated();
  a.for_each_tile([&](CellIndex origin, const PackedMass* cells) {
    for (int i = 0; i < DsGrid::kTileCells && same; ++i) {
      const CellIndex c = DsGrid::tile_cell(origin, i);
      same = b.at(c).occupied == cells[i].mass().occupied && b.at(c).free == cells[i].mass().free;
    }
  });
  return same;
}

TEST(MapMerge, AtIdentityEveryCellIsTheDempsterCombination) {
  MultiResMap a, b;
  a.mutable_level(0).set({3, 4}, {0.5f, 0.1f});
  b.mutable_level(0).set({3, 4}, {0.3f, 0.2f});
  b.mutable_level(0).set({-20, 7}, {0.0f, 0.6f});
  combine_into(a, b, Pose2{});
  const DsMass expected = a.config().evidence.update({0.5f, 0.1f}, {0.3f, 0.2f});
  // Cells hold 16-bit masses: the two inputs and the result round by half a step each.
  EXPECT_NEAR(a.finest().at({3, 4}).occupied, expected.occupied, 3e-5);
  EXPECT_NEAR(a.finest().at({3, 4}).free, expected.free, 3e-5);
  EXPECT_NEAR(a.finest().at({-20, 7}).free, 0.6f, 1e-5);
  EXPECT_EQ(a.finest().at({100, 100}).occupied, 0.0f);  // nothing known there
}

TEST(MapMerge, ResamplingSkipsOnlyCellsThatCanReadNothing) {
  // Patches of evidence scattered over a source moved and turned into a
  // target with evidence of its own: the combination, which skips tiles and
  // 16×16 blocks whose place in the source is empty, against every target
  // cell resampled one by one.
  MultiResMap source, target;
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::int32_t> place(-400, 400);
  // Single cells, many: some lie at the very edge of what a block can read.
  for (MultiResMap* map : {&source, &target})
    for (int k = 0; k < 3000; ++k) map->mutable_level(0).set({place(rng), place(rng)}, {0.55f, 0.15f});
  // Turned (blocks read rotated boxes) and only moved (boxes read exactly).
  for (const Pose2& move : {Pose2(1.37, -2.11, 0.7), Pose2(1.37, -2.11, 0.0)}) {
    MultiResMap combined = target;
    combine_into(combined, source, move);
    const PointTransform to_source(move.inverse());
    const double r = target.config().resolution;
    std::size_t changed = 0;
    for (std::int32_t y = -700; y < 700; ++y)
      for (std::int32_t x = -700; x < 700; ++x) {
        const Eigen::Vector2d p = to_source((x + 0.5) * r, (y + 0.5) * r);
        const DsMass m = interpolated_masses(source.finest(), p.x(), p.y());
        PackedMass expected = target.finest().packed_at({x, y});
        if (m.occupied + m.free >= 1e-4f) {  // map_combine's "knows nothing" threshold
          expected = PackedMass::pack(target.config().evidence.update(expected.mass(), m));
          ++changed;
        }
        ASSERT_EQ(combined.finest().packed_at({x, y}), expected) << x << ", " << y << " turned " << move.theta;
      }
    EXPECT_GT(changed, 3000u);
  }
}

TEST(MapMerge, ForeignMapLandsOnTheSameWallsThroughTheTransform) {
  const World world = test::l_shaped_office();
  Rng rng(3);
  // Robot A's frame starts at (1, 1, 0); robot B's at (8, 2, 2.0) — rotated.
  const Pose2 a_frame{1.0, 1.0, 0.0}, b_frame{8.0, 2.0, 2.0};
  const MultiResMap only_b = test::map_from(world, {{8.0, 2.0, 2.0}, {6.0, 2.5, 0.5}}, b_frame, rng);
  MultiResMap a = test::map_from(world, {{2.0, 1.5, 0.0}}, a_frame, rng);
  const Pose2 b_in_a = a_frame.inverse() * b_frame;
  combine_into(a, only_b, b_in_a);
  // A scan taken where only B had been fits A's merged map at the true pose…
  const Pose2 probe{7.0, 2.8, -1.0};
  const auto points = test::scan_at(world, probe, rng);
  const double right = score_pose(a.finest(), points, a_frame.inverse() * probe);
  // …and clearly worse through a wrong transform.
  MultiResMap wrong = test::map_from(world, {{2.0, 1.5, 0.0}}, a_frame, rng);
  combine_into(wrong, only_b, b_in_a * Pose2{0.3, 0.0, 0.1});
  const double off = score_pose(wrong.finest(), points, a_frame.inverse() * probe);
  EXPECT_GT(right, 0.3);
  EXPECT_GT(right, 2.0 * off);
}

// A robot with loop closure on sends its finished submaps apart, each at its
// pose in the robot's frame: the copy another robot holds follows the
// sender's later loop closures, since a newer snapshot moves the pieces.
TEST(MapMerge, PiecesLandWhereTheSendersLatestSnapshotPutsThem) {
  const World world = test::l_shaped_office();
  Rng rng(3);
  const Pose2 a_frame{1.0, 1.0, 0.0}, b_frame{8.0, 2.0, 2.0};
  const Pose2 b_in_a = a_frame.inverse() * b_frame;
  const MultiResMap b_submap = test::map_from(world, {{8.0, 2.0, 2.0}, {6.0, 2.5, 0.5}}, b_frame, rng);
  const auto frozen = std::make_shared<const FrozenMap>(b_submap);
  const auto growing = std::make_shared<const MultiResMap>(b_submap.config());  // B's next submap: empty yet
  // Before B closed a loop it had this submap 0.3 m and 3 degrees off; after, where it is.
  const MapLayer before{"b", 10, Pose2{}, 0, growing, {{4, Pose2{0.3, -0.2, 0.05}, frozen}}};
  MapLayer after = before;
  after.version = 20;
  after.pieces.front().pose = Pose2{};
  const MultiResMap own = test::map_from(world, {{2.0, 1.5, 0.0}}, a_frame, rng);
  MapKnowledge a("a");
  ASSERT_TRUE(a.absorb(MapSnapshot{"b", {before}}, b_in_a));
  const MultiResMap stale = compose_working_map(own, a.layers());
  ASSERT_TRUE(a.absorb(MapSnapshot{"b", {after}}, b_in_a));
  EXPECT_FALSE(a.absorb(MapSnapshot{"b", {before}}, b_in_a));  // older: changes nothing
  const MultiResMap now = compose_working_map(own, a.layers());
  // A scan where only B had been fits the map at the true pose once the piece moved.
  const Pose2 probe{7.0, 2.8, -1.0};
  const auto points = test::scan_at(world, probe, rng);
  const double right = score_pose(now.finest(), points, a_frame.inverse() * probe);
  const double off = score_pose(stale.finest(), points, a_frame.inverse() * probe);
  EXPECT_GT(right, 0.3);
  EXPECT_GT(right, 2.0 * off);
  // The layer's evidence in B's frame is the piece where it is (the growing submap is empty).
  MultiResMap placed(b_submap.config());
  combine_into(placed, frozen->thaw(b_submap.config()), Pose2{});
  EXPECT_TRUE(same_cells(layer_evidence(after).finest(), placed.finest()));
}

TEST(MapMerge, ComposeIgnoresTheOrderLayersArriveIn) {
  const World world = test::l_shaped_office();
  Rng rng(5);
  const MultiResMap own = test::map_from(world, {{2.0, 1.5, 0.0}}, Pose2{}, rng);
  auto layer = [&](const char* origin, const Pose2& frame, const Pose2& at) {
    return MapLayer{origin, 10, frame, 1, std::make_shared<const MultiResMap>(test::map_from(world, {at}, frame, rng)), {}};
  };
  const MapLayer b = layer("b", {5.0, 1.0, 0.3}, {6.0, 2.0, 0.0});
  const MapLayer c = layer("c", {2.0, 7.0, -1.2}, {2.0, 6.0, 1.0});
  const MultiResMap bc = compose_working_map(own, {b, c});
  const MultiResMap cb = compose_working_map(own, {c, b});
  for (int level = 0; level < own.levels(); ++level) EXPECT_TRUE(same_cells(bc.level(level), cb.level(level)));
  // And the foreign evidence is really there.
  EXPECT_FALSE(same_cells(bc.finest(), own.finest()));
}

TEST(MapMerge, RefusesMapsOfAnotherResolution) {
  MultiResMap a;
  MapConfig coarse;
  coarse.resolution = 0.1;
  const MultiResMap b(coarse);
  EXPECT_THROW(combine_into(a, b, Pose2{}), ConfigError);
}

}  // namespace
}  // namespace dsswarm
