#include "grid/ds_grid.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace dsswarm {
namespace {

constexpr float kStep = 1.0f / PackedMass::kOne;  // cells hold 16-bit masses

TEST(DsGrid, UnwrittenCellsAreUnknownAndAllocateNothing) {
  const DsGrid g(0.05);
  EXPECT_EQ(g.at({123, -456}).unknown(), 1.0f);
  EXPECT_EQ(g.tiles_allocated(), 0u);
}

TEST(DsGrid, HoldsEvidenceOnlyWhereACellKnowsSomething) {
  DsGrid g(0.05);
  EXPECT_FALSE(g.holds_evidence());
  g.set({10, -3}, DsMass{});  // allocates a tile of vacuous cells
  EXPECT_GT(g.tiles_allocated(), 0u);
  EXPECT_FALSE(g.holds_evidence());
  g.set({10, -3}, DsMass{kStep, 0.0f});
  EXPECT_TRUE(g.holds_evidence());
}

TEST(DsGrid, GrowsInEveryDirection) {
  DsGrid g(0.05);
  const CellIndex far[] = {{0, 0}, {-5000, 3}, {7000, -9000}, {-70000, 80000}, {12, 12}};
  float v = 0.1f;
  for (const CellIndex& c : far) {
    g.set(c, {v, 0.0f});
    v += 0.1f;
  }
  v = 0.1f;
  for (const CellIndex& c : far) {
    EXPECT_NEAR(g.at(c).occupied, v, kStep);
    v += 0.1f;
  }
  EXPECT_EQ(g.tiles_allocated(), 4u);  // (0,0) and (12,12) share a tile
  // Neighbours in the same tile are untouched.
  EXPECT_EQ(g.at({-5001, 3}).occupied, 0.0f);
}

TEST(DsGrid, CellOfHandlesNegativeCoordinates) {
  const DsGrid g(0.1);
  EXPECT_EQ(g.cell_of({0.05, 0.05}), (CellIndex{0, 0}));
  EXPECT_EQ(g.cell_of({-0.05, -0.15}), (CellIndex{-1, -2}));
  const Eigen::Vector2d c = g.cell_center({-1, 2});
  EXPECT_NEAR(c.x(), -0.05, 1e-12);
  EXPECT_NEAR(c.y(), 0.25, 1e-12);
}

TEST(DsGrid, CellsAreCompact) {
  DsGrid g(0.05);
  for (int i = 0; i < 20; ++i) g.set({i * 64, 0}, {0.5f, 0.0f});
  const double bytes_per_cell = static_cast<double>(g.memory_bytes()) / static_cast<double>(g.cells_allocated());
  EXPECT_LT(bytes_per_cell, 4.2);  // two 16-bit masses per cell plus a little table overhead
}

TEST(DsGrid, RasterCoversEvidenceWithRowZeroAtLowestY) {
  DsGrid g(0.5);
  g.set({-3, -2}, {0.9f, 0.0f});
  g.set({4, 5}, {0.0f, 0.8f});
  const GridRaster r = g.to_raster(1);
  EXPECT_EQ(r.width, 4 + 3 + 1 + 2);
  EXPECT_EQ(r.height, 5 + 2 + 1 + 2);
  EXPECT_NEAR(r.origin.x(), -2.0, 1e-12);  // (-3 - 1) * 0.5
  EXPECT_NEAR(r.origin.y(), -1.5, 1e-12);
  EXPECT_NEAR(r.at(1, 1).occupied, 0.9f, kStep);
  EXPECT_NEAR(r.at(r.width - 2, r.height - 2).free, 0.8f, kStep);
}

}  // namespace
}  // namespace dsswarm

namespace dsswarm {
namespace {

TEST(DsGrid, QuadMatchesFourLookupsInsideAndAcrossTiles) {
  DsGrid g(0.05);
  for (int y = -70; y < 70; y += 3)
    for (int x = -70; x < 70; x += 2) g.set({x, y}, {0.001f * static_cast<float>(x + 70), 0.0005f * static_cast<float>(y + 70)});
  for (const CellIndex c : {CellIndex{0, 0}, CellIndex{62, 5}, CellIndex{63, 5}, CellIndex{5, 63}, CellIndex{63, 63},
                            CellIndex{-1, -1}, CellIndex{-65, 10}, CellIndex{500, 500}}) {
    DsMass q[4];
    g.quad(c, q);
    const CellIndex cells[4] = {c, {c.x + 1, c.y}, {c.x, c.y + 1}, {c.x + 1, c.y + 1}};
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(q[k].occupied, g.at(cells[k]).occupied) << c.x << "," << c.y << " #" << k;
      EXPECT_EQ(q[k].free, g.at(cells[k]).free) << c.x << "," << c.y << " #" << k;
    }
  }
}

TEST(DsGrid, CopyIsDeepAndIndependent) {
  DsGrid a(0.1);
  a.set({-70, 5}, {0.5f, 0.1f});
  a.set({200, -300}, {0.2f, 0.3f});
  DsGrid b = a;
  EXPECT_EQ(b.tiles_allocated(), a.tiles_allocated());
  EXPECT_NEAR(b.at({-70, 5}).occupied, 0.5f, kStep);
  EXPECT_NEAR(b.at({200, -300}).free, 0.3f, kStep);
  b.set({-70, 5}, {0.0f, 0.9f});
  b.set({1000, 1000}, {0.7f, 0.0f});
  EXPECT_NEAR(a.at({-70, 5}).occupied, 0.5f, kStep);  // the original is untouched
  EXPECT_EQ(a.at({1000, 1000}).occupied, 0.0f);
  a = b;
  EXPECT_NEAR(a.at({1000, 1000}).occupied, 0.7f, kStep);
}

TEST(DsGrid, AbsorbTakesOverTheOtherGridsTilesAndRefusesOverlap) {
  DsGrid a(0.1), b(0.1);
  a.set({5, 5}, {0.5f, 0.1f});
  b.set({-500, 700}, {0.2f, 0.3f});  // outside a's table: it grows
  b.set({70, 5}, {0.1f, 0.6f});
  a.absorb(std::move(b));
  EXPECT_EQ(a.tiles_allocated(), 3u);
  EXPECT_EQ(b.tiles_allocated(), 0u);
  EXPECT_NEAR(a.at({5, 5}).occupied, 0.5f, kStep);
  EXPECT_NEAR(a.at({-500, 700}).free, 0.3f, kStep);
  EXPECT_NEAR(a.at({70, 5}).free, 0.6f, kStep);
  a.set({-501, 701}, {0.4f, 0.0f});  // the absorbed tile is a's own now
  EXPECT_NEAR(a.at({-501, 701}).occupied, 0.4f, kStep);
  DsGrid c(0.1);
  c.set({6, 6}, {0.3f, 0.0f});  // the tile of a's (5, 5)
  EXPECT_THROW(a.absorb(std::move(c)), std::logic_error);
  DsGrid coarse(0.2);
  EXPECT_THROW(a.absorb(std::move(coarse)), std::logic_error);
}

}  // namespace
}  // namespace dsswarm
