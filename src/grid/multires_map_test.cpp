#include "grid/multires_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "grid/sampling.hpp"

namespace dsswarm {
namespace {

TEST(MultiResMap, LevelsDoubleInCellSize) {
  const MultiResMap map(MapConfig{0.05, 3, {}, true, false});
  ASSERT_EQ(map.levels(), 3);
  EXPECT_DOUBLE_EQ(map.level(1).resolution(), 0.1);
  EXPECT_DOUBLE_EQ(map.level(2).resolution(), 0.2);
}

// Insertion skips cells a pass leaves unchanged: the cells a beam crosses
// over and over must still end exactly as passes applied one by one leave them.
TEST(MultiResMap, RepeatedPassesGiveWhatEachPassGivesOneByOne) {
  const EvidenceModel ev;
  const std::vector<ScanPoint> beam = {{3.0f, 0.0f, 1.0f}};
  const CellIndex crossed{20, 0};  // 1 m along the beam, far from its end
  for (const int scans : {1, 5, 60, 400}) {
    MultiResMap map(MapConfig{0.05, 1, {}, false, false});
    for (int k = 0; k < scans; ++k) map.insert_scan(Pose2(0.01, 0.01, 0.0), Pose2(), beam);
    PackedMass expected{};
    for (int k = 0; k < scans; ++k) expected = PackedMass::pack_valid(ev.update_passed(expected.unguarded_mass()));
    const PackedMass got = map.level(0).packed_at(crossed);
    EXPECT_EQ(got.occupied, expected.occupied) << scans << " scans";
    EXPECT_EQ(got.free, expected.free) << scans << " scans";
  }
  // 400 passes reach the cap the discount sets.
  MultiResMap map(MapConfig{0.05, 1, {}, false, false});
  for (int k = 0; k < 400; ++k) map.insert_scan(Pose2(0.01, 0.01, 0.0), Pose2(), beam);
  EXPECT_NEAR(map.level(0).at(crossed).free, 1.0f - ev.min_unknown, 1e-3f);
}

// Hits are written a run at a time: consecutive hits on one cell (or one
// 2×2 block, on coarse levels) combine before the write. The cell must end
// as Dempster's rule applied hit by hit leaves it, runs broken up or not.
TEST(MultiResMap, HitsInOneCellCombineAsWrittenOneByOne) {
  const EvidenceModel ev;
  // Three returns in the cell around (2.02, 0.02), one elsewhere, then one more in the first cell.
  const std::vector<ScanPoint> hits = {{2.01f, 0.01f, 1.0f}, {2.02f, 0.02f, 1.0f}, {2.03f, 0.03f, 1.0f},
                                       {2.01f, 0.6f, 1.0f},  {2.02f, 0.01f, 1.0f}};
  MapConfig config{0.05, 2, {}, false, false};
  config.surface_gap = 0.0;  // hits alone
  MultiResMap map(config);
  map.insert_scan(Pose2(), Pose2(), hits);
  DsMass expected = DsMass::vacuous();
  for (int k = 0; k < 4; ++k) expected = ev.update(expected, ev.hit());
  const DsGrid& fine = map.level(0);
  EXPECT_NEAR(fine.at(fine.cell_of({2.02, 0.02})).occupied, expected.occupied, 2e-4f);
  EXPECT_NEAR(fine.at(fine.cell_of({2.01, 0.6})).occupied, ev.hit_occupied, 2e-4f);
  // Coarse level: each hit spreads over four cells; their sum of shares, combined, for each.
  const DsGrid& coarse = map.level(1);
  for (const CellIndex c : {CellIndex{19, -1}, CellIndex{20, -1}, CellIndex{19, 0}, CellIndex{20, 0}}) {
    DsMass cell = DsMass::vacuous();
    for (const ScanPoint& p : hits) {
      const BilinearPoint b = bilinear_point(p.x, p.y, 1.0 / coarse.resolution());
      const std::array<float, 4> w = b.weights();
      for (int k = 0; k < 4; ++k) {
        const CellIndex at{b.corner.x + (k & 1), b.corner.y + (k >> 1)};
        if (at == c && w[static_cast<std::size_t>(k)] > 0.0f)
          cell = ev.update(cell, {ev.hit_occupied * w[static_cast<std::size_t>(k)], 0.0f});
      }
    }
    EXPECT_NEAR(coarse.at(c).occupied, cell.occupied, 2e-4f) << c.x << "," << c.y;
  }
}

TEST(MultiResMap, BeamMarksHitOccupiedAndPathFreeOnEveryLevel) {
  MultiResMap map(MapConfig{0.05, 2, {}, true, false});
  const std::vector<ScanPoint> pts = {{2.0f, 0.0f, 1.0f}};
  map.insert_scan(Pose2(0.01, 0.01, 0.0), Pose2(), pts);
  const EvidenceModel ev;
  for (int l = 0; l < 2; ++l) {
    const DsGrid& g = map.level(l);
    // One hit: exactly the hit mass on level 0; coarse levels spread it over
    // the four nearest cells, so the cell holding the point gets a share.
    if (l == 0) {
      EXPECT_NEAR(g.at(g.cell_of({2.01, 0.01})).occupied, ev.hit_occupied, 1e-5);
    } else {
      EXPECT_GT(g.at(g.cell_of({2.01, 0.01})).occupied, 0.1f * ev.hit_occupied) << "level " << l;
    }
    // One pass (free_space_on_coarse_levels): exactly the free mass.
    EXPECT_NEAR(g.at(g.cell_of({1.0, 0.01})).free, ev.pass_free, 1e-5) << "level " << l;
    EXPECT_FLOAT_EQ(g.at(g.cell_of({1.0, 1.0})).unknown(), 1.0f);
  }
}

TEST(MultiResMap, ScanIsPlacedByRobotPoseAndLaserOffset) {
  MultiResMap map(MapConfig{0.05, 1, {}, true, false});
  const std::vector<ScanPoint> pts = {{1.0f, 0.0f, 1.0f}};  // base frame
  map.insert_scan(Pose2(5.0, 5.0, std::numbers::pi / 2), Pose2(0.2, 0.0, 0.0), pts);
  const DsGrid& g = map.finest();
  const EvidenceModel ev;
  EXPECT_NEAR(g.at(g.cell_of({5.0, 6.0})).occupied, ev.hit_occupied, 1e-5);
  // The beam starts at the laser (0.2 m ahead of the base): cells behind it stay unknown.
  EXPECT_FLOAT_EQ(g.at(g.cell_of({5.0, 5.1})).unknown(), 1.0f);
  EXPECT_NEAR(g.at(g.cell_of({5.0, 5.5})).free, ev.pass_free, 1e-5);
}

// map.free_margin_cells: free evidence stops that many cells short of the hit.
TEST(MultiResMap, FreeMarginStopsFreeEvidenceShortOfTheHit) {
  auto map_after_beam = [](double margin_cells, float hit_x) {
    MapConfig config{0.05, 1, {}, false, false};
    config.free_margin_cells = margin_cells;
    MultiResMap map(config);
    map.insert_scan(Pose2(0.0, 0.012, 0.0), Pose2(), {{hit_x, 0.0f, 1.0f}});
    return map;
  };
  const float pass_free = EvidenceModel{}.pass_free;
  const MultiResMap with = map_after_beam(1.0, 2.02f);
  const DsGrid& g = with.finest();
  EXPECT_FLOAT_EQ(g.at(g.cell_of({1.99, 0.012})).unknown(), 1.0f);  // the cell just before the hit's
  EXPECT_NEAR(g.at(g.cell_of({1.94, 0.012})).free, pass_free, 1e-5);
  EXPECT_GT(g.at(g.cell_of({2.02, 0.012})).occupied, 0.0f);
  EXPECT_FLOAT_EQ(g.at(g.cell_of({2.02, 0.012})).free, 0.0f);
  const MultiResMap without = map_after_beam(0.0, 2.02f);  // no margin
  EXPECT_NEAR(without.finest().at(g.cell_of({1.99, 0.012})).free, pass_free, 1e-5);
  EXPECT_FLOAT_EQ(without.finest().at(g.cell_of({2.02, 0.012})).free, 0.0f);
  // A hit closer than the margin adds no free evidence at all.
  const MultiResMap close = map_after_beam(10.0, 0.3f);
  EXPECT_FLOAT_EQ(close.finest().at(g.cell_of({0.1, 0.012})).unknown(), 1.0f);
}

TEST(MultiResMap, RejectsBadConfig) {
  EXPECT_THROW(MultiResMap(MapConfig{0.0, 3, {}, true, false}), ConfigError);
  EXPECT_THROW(MultiResMap(MapConfig{0.05, 0, {}, true, false}), ConfigError);
  MapConfig negative_margin;
  negative_margin.free_margin_cells = -1.0;
  EXPECT_THROW(MultiResMap{negative_margin}, ConfigError);
}

// Inserting into several maps at once (the current and the previous submap)
// leaves each exactly as inserting into it alone: beams that cross many
// tiles, in every direction, on both sides of the origin.
TEST(MultiResMap, InsertingIntoTwoMapsAtOnceEqualsInsertingIntoEach) {
  std::vector<ScanPoint> pts;
  for (int i = 0; i < 360; ++i) {
    const double a = i * 0.0174533, r = 1.0 + 9.0 * std::abs(std::sin(3.0 * a));
    pts.push_back({static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), 1.0f});
  }
  const std::vector<Pose2> poses{Pose2(0.3, -0.2, 0.1), Pose2(-4.1, 2.7, 2.0), Pose2(1.0, 1.0, -1.2)};
  MultiResMap alone_a, alone_b, together_a, together_b;
  alone_b.insert_scan(Pose2(5, 5, 0), Pose2(), pts);  // b starts with a different history
  together_b.insert_scan(Pose2(5, 5, 0), Pose2(), pts);
  MultiResMap* both[] = {&together_a, &together_b};
  for (const Pose2& p : poses) {
    alone_a.insert_scan(p, Pose2(), pts);
    alone_b.insert_scan(p, Pose2(), pts);
    MultiResMap::insert_scan(both, p, Pose2(), pts);
  }
  for (int l = 0; l < alone_a.levels(); ++l) {
    for (const auto& [alone, together] : {std::pair{&alone_a, &together_a}, std::pair{&alone_b, &together_b}}) {
      const GridRaster x = alone->level(l).to_raster(), y = together->level(l).to_raster();
      ASSERT_EQ(x.width, y.width);
      ASSERT_EQ(x.height, y.height);
      ASSERT_GT(x.cells.size(), 1000u);
      for (std::size_t i = 0; i < x.cells.size(); ++i) {
        ASSERT_EQ(x.cells[i].occupied, y.cells[i].occupied) << "level " << l << " cell " << i;
        ASSERT_EQ(x.cells[i].free, y.cells[i].free) << "level " << l << " cell " << i;
      }
    }
  }
}

}  // namespace
}  // namespace dsswarm
