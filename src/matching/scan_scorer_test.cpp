#include "matching/scan_scorer.hpp"

#include <gtest/gtest.h>

#include <random>

namespace dsswarm {
namespace {

// A grid with random masses over several tiles on both sides of the origin,
// so that blocks straddle tile edges and negative indices round down.
DsGrid random_grid(std::mt19937& rng) {
  DsGrid grid(0.05);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int y = -90; y < 90; ++y)
    for (int x = -90; x < 90; ++x) {
      if (u(rng) < 0.3f) continue;  // some cells stay vacuous
      const float o = u(rng);
      grid.set({x, y}, {o, (1.0f - o) * u(rng)});
    }
  return grid;
}

std::vector<ScanPoint> random_points(std::mt19937& rng, int n) {
  std::uniform_real_distribution<float> r(-6.0f, 6.0f);
  std::uniform_real_distribution<float> w(0.1f, 2.0f);
  std::vector<ScanPoint> points;
  for (int i = 0; i < n; ++i) {
    ScanPoint p;
    p.x = r(rng);
    p.y = r(rng);
    p.weight = w(rng);
    points.push_back(p);
  }
  return points;
}

// The score as eq. (1) states it, point by point through the grid's public
// reads: what the prepared scorer must reproduce.
double reference_score(const DsGrid& grid, const std::vector<ScanPoint>& points, const Pose2& pose,
                       std::size_t stride, float unknown_value) {
  const PointTransform to_world(pose);
  double sum = 0.0, weights = 0.0;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    const Eigen::Vector2d w = to_world(points[i].x, points[i].y);
    sum += points[i].weight * interpolated_occupancy(grid, w.x(), w.y(), unknown_value);
    weights += points[i].weight;
  }
  return sum / weights;
}

TEST(ScanScorer, EqualsThePointByPointScoreAcrossTilesStridesAndUnknownShares) {
  std::mt19937 rng(7);
  const DsGrid grid = random_grid(rng);
  const std::vector<ScanPoint> points = random_points(rng, 301);
  std::uniform_real_distribution<double> xy(-2.0, 2.0), th(-3.1, 3.1);
  int compared = 0;
  for (float unknown_value : {0.0f, 0.5f})
    for (std::size_t stride : {std::size_t{1}, std::size_t{2}, std::size_t{4}}) {
      const ScanScorer scorer(grid, points, stride, unknown_value);
      for (int k = 0; k < 20; ++k) {
        const Pose2 pose(xy(rng), xy(rng), th(rng));
        const double expected = reference_score(grid, points, pose, stride, unknown_value);
        EXPECT_NEAR(scorer.score(pose), expected, 1e-5) << "stride " << stride << " unknown " << unknown_value;
        ++compared;
      }
    }
  EXPECT_EQ(compared, 120);
}

TEST(ScanScorer, PointsOutsideTheMapScoreTheVacuousValue) {
  const DsGrid empty(0.05);
  std::mt19937 rng(3);
  const std::vector<ScanPoint> points = random_points(rng, 50);
  EXPECT_EQ(ScanScorer(empty, points).score(Pose2(1, 2, 0.3)), 0.0);
  EXPECT_NEAR(ScanScorer(empty, points, 1, 0.5f).score(Pose2(1, 2, 0.3)), 0.5, 1e-6);
}

TEST(ScanScorer, NoWeightScoresZero) {
  DsGrid grid(0.05);
  grid.set({0, 0}, {0.9f, 0.0f});
  std::vector<ScanPoint> points(3);
  for (ScanPoint& p : points) p.weight = 0.0f;
  EXPECT_EQ(ScanScorer(grid, points).score(Pose2()), 0.0);
  EXPECT_EQ(ScanScorer(grid, {}).score(Pose2()), 0.0);
}

}  // namespace
}  // namespace dsswarm
