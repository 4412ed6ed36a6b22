#include "grid/ray_traversal.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace dsswarm {
namespace {

std::vector<CellIndex> trace(Eigen::Vector2d a, Eigen::Vector2d b, double res) {
  std::vector<CellIndex> cells;
  traverse_ray(a, b, res, [&](CellIndex c) { cells.push_back(c); });
  return cells;
}

TEST(RayTraversal, HorizontalRayVisitsCellsUpToButExcludingTheHit) {
  const auto cells = trace({0.05, 0.05}, {0.45, 0.05}, 0.1);
  ASSERT_EQ(cells.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(cells[i], (CellIndex{i, 0}));
}

TEST(RayTraversal, NegativeDirectionAndCoordinates) {
  const auto cells = trace({0.05, 0.05}, {-0.25, 0.05}, 0.1);
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_EQ(cells[0], (CellIndex{0, 0}));
  EXPECT_EQ(cells[2], (CellIndex{-2, 0}));
}

TEST(RayTraversal, DiagonalCellsAreFourConnectedAndEndNextToTheHit) {
  const Eigen::Vector2d a{0.013, 0.027}, b{1.37, -0.91};
  const auto cells = trace(a, b, 0.05);
  ASSERT_FALSE(cells.empty());
  EXPECT_EQ(cells.front(), (CellIndex{0, 0}));
  for (std::size_t i = 1; i < cells.size(); ++i)
    EXPECT_EQ(std::abs(cells[i].x - cells[i - 1].x) + std::abs(cells[i].y - cells[i - 1].y), 1);
  const CellIndex hit{static_cast<int>(std::floor(b.x() / 0.05)), static_cast<int>(std::floor(b.y() / 0.05))};
  const CellIndex last = cells.back();
  EXPECT_EQ(std::abs(hit.x - last.x) + std::abs(hit.y - last.y), 1);
  EXPECT_EQ(cells.size(), static_cast<std::size_t>(std::abs(hit.x) + std::abs(hit.y)));
}

TEST(RayTraversal, SameCellVisitsNothing) {
  EXPECT_TRUE(trace({0.01, 0.01}, {0.02, 0.03}, 0.1).empty());
}

// The writers' traversal must give exactly traverse_ray's cells, in order,
// and announce a tile only before cells of it: beams of every direction and
// length, across tile borders on both sides of the origin.
TEST(RayTraversal, ByTileGivesTheSameCellsAndEntersOnlyTheirTiles) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-12.0, 12.0);
  constexpr double kRes = 0.05;
  int tiles_entered = 0;
  for (int ray = 0; ray < 2000; ++ray) {
    const Eigen::Vector2d a{coordinate(rng), coordinate(rng)};
    const Eigen::Vector2d b = ray % 4 == 0 ? Eigen::Vector2d(a.x() + coordinate(rng), a.y())  // axis-parallel too
                                           : Eigen::Vector2d(coordinate(rng), coordinate(rng));
    const std::vector<CellIndex> want = trace(a, b, kRes);
    std::vector<CellIndex> got;
    CellIndex tile{};
    int announced = 0, empty_tiles = 0, visits_in_tile = 0;
    traverse_ray_by_tile(
        a, b, kRes,
        [&](CellIndex c) {
          if (announced > 0 && visits_in_tile == 0) ++empty_tiles;
          tile = {c.x & ~(DsGrid::kTileSize - 1), c.y & ~(DsGrid::kTileSize - 1)};
          ++announced;
          visits_in_tile = 0;
        },
        [&](int local) {
          got.push_back(DsGrid::tile_cell(tile, local));  // wrong if a tile went unannounced
          ++visits_in_tile;
        });
    if (announced > 0 && visits_in_tile == 0) ++empty_tiles;
    EXPECT_EQ(empty_tiles, 0) << "ray " << ray;
    tiles_entered += announced;
    ASSERT_EQ(got, want) << "ray " << ray;
  }
  EXPECT_GT(tiles_entered, 2000);
}

}  // namespace
}  // namespace dsswarm
