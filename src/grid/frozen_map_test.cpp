#include "grid/frozen_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace dsswarm {
namespace {

MultiResMap some_map() {
  MultiResMap map;
  std::vector<ScanPoint> points;
  for (int i = 0; i < 90; ++i) {
    const double a = -1.5 + i * 0.033;
    points.push_back({static_cast<float>(4.0 * std::cos(a)), static_cast<float>(4.0 * std::sin(a)), 1.0f});
  }
  map.insert_scan(Pose2(1, 2, 0.3), Pose2(), points);
  map.insert_scan(Pose2(1.2, 2.1, 0.35), Pose2(), points);
  return map;
}

TEST(FrozenMap, HoldsEvidenceAsTheLiveMapDid) {
  EXPECT_TRUE(FrozenMap(some_map()).holds_evidence());
  EXPECT_FALSE(FrozenMap(MultiResMap()).holds_evidence());
  MultiResMap vacuous;
  vacuous.mutable_level(0).set({3, 4}, DsMass{});
  EXPECT_FALSE(FrozenMap(vacuous).holds_evidence());
}

TEST(FrozenMap, ThawsToTheSameCellsWithinItsPrecision) {
  const MultiResMap map = some_map();
  const FrozenMap frozen(map);
  const MultiResMap back = frozen.thaw(map.config());
  std::size_t cells = 0;
  for (int l = 0; l < map.levels(); ++l)
    map.level(l).for_each_tile([&](CellIndex origin, const PackedMass* masses) {
      for (int i = 0; i < DsGrid::kTileCells; ++i) {
        const DsMass m = masses[i].mass();
        const DsMass b = back.level(l).at(DsGrid::tile_cell(origin, i));
        // Square-root scale: the error grows with the mass, 1% of one beam's free mass.
        EXPECT_NEAR(b.occupied, m.occupied, 0.0005 + 0.004 * std::sqrt(m.occupied));
        EXPECT_NEAR(b.free, m.free, 0.0005 + 0.004 * std::sqrt(m.free));
        EXPECT_LE(b.occupied + b.free, 1.0f);
        if (m.occupied + m.free > 0.0f) ++cells;
      }
    });
  EXPECT_GT(cells, 1000u);
  // Vacuous cells stay vacuous, and unknown space allocates nothing.
  EXPECT_EQ(back.finest().at({-500, 700}).occupied, 0.0f);
  EXPECT_LE(back.finest().tiles_allocated(), map.finest().tiles_allocated());
}

TEST(FrozenMap, IsAFractionOfTheLiveMap) {
  const MultiResMap map = some_map();
  EXPECT_LT(FrozenMap(map).memory_bytes() * 20, map.memory_bytes());
}

}  // namespace
}  // namespace dsswarm
