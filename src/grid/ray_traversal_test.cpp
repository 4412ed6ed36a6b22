#include "grid/ray_traversal.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace dsswarm
