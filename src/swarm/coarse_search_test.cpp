#include "swarm/coarse_search.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "grid/sampling.hpp"
#include "swarm/test_scenes.hpp"

namespace dsswarm {
namespace {

// Every lattice pose, scored the plain way: each point read through
// interpolated_occupancy, the order the search promises.
TEST(CoarseSearch, ScoresEveryLatticePoseAsTheMapReadsThePoints) {
  const World world = test::l_shaped_office();
  Rng rng(5);
  const MultiResMap map = test::map_from(world, {{2.0, 1.5, 0.3}, {3.0, 2.5, 1.0}, {5.5, 2.0, 0.0}}, Pose2{}, rng);
  std::vector<ScanPoint> points = test::scan_at(world, {3.5, 2.0, 2.0}, rng);
  RelativePoseConfig config;
  config.coarse_points = static_cast<int>(points.size());  // every point: no thinning to replay
  config.search_radius = 1.0;
  const DsGrid& grid = map.level(map.levels() - 1);
  const Eigen::Vector2d near{3.0, 2.5};
  const std::vector<CoarsePlacement> all = exhaustive_search(grid, points, near, config);

  double weight_sum = 0.0;
  for (const ScanPoint& p : points) weight_sum += p.weight;
  const int steps = static_cast<int>(std::floor(config.search_radius / config.coarse_step_xy));
  std::size_t k = 0;
  for (int h = 0; h < 120; ++h)
    for (int iy = -steps; iy <= steps; ++iy)
      for (int ix = -steps; ix <= steps; ++ix) {
        if (ix * ix + iy * iy > steps * steps) continue;
        ASSERT_LT(k, all.size());
        const Pose2 pose{near.x() + ix * config.coarse_step_xy, near.y() + iy * config.coarse_step_xy,
                         -std::numbers::pi + 2.0 * std::numbers::pi * h / 120};
        const PointTransform to_world(PointTransform::rotation(pose.theta));
        double sum = 0.0;
        for (const ScanPoint& p : points) {
          const Eigen::Vector2d r = to_world(p.x, p.y);
          sum += p.weight * interpolated_occupancy(grid, pose.x + r.x(), pose.y + r.y(), 0.0f);
        }
        EXPECT_EQ(all[k].pose.x, pose.x);
        EXPECT_EQ(all[k].pose.y, pose.y);
        EXPECT_EQ(all[k].pose.theta, pose.theta);
        ASSERT_EQ(all[k].score, static_cast<float>(sum / weight_sum)) << "lattice pose " << k;
        ++k;
      }
  EXPECT_EQ(k, all.size());
}

// The slices sorted one at a time pick what ranking everything would pick,
// ties included (many equal scores, as empty space gives); on odd trials the
// poses crowd together, so that few are distinct and the picking reads
// through every slice.
TEST(CoarseSearch, TheDistinctBestAreThoseOfTheWholeRanking) {
  RelativePoseConfig config;
  Rng rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<CoarsePlacement> all(20000 + 3000 * static_cast<std::size_t>(trial));
    const double spread = trial % 2 == 1 ? 0.2 : 1.0;
    for (std::size_t i = 0; i < all.size(); ++i)
      all[i] = {static_cast<float>(std::floor(rng.uniform(0.0, 8.0)) / 8.0), static_cast<std::uint32_t>(i),
                Pose2{spread * rng.uniform(-3.0, 3.0), spread * rng.uniform(-3.0, 3.0), spread * rng.uniform(-3.1, 3.1)}};
    std::vector<CoarsePlacement> ranked = all;
    std::stable_sort(ranked.begin(), ranked.end(),
                     [](const CoarsePlacement& a, const CoarsePlacement& b) { return a.score > b.score; });
    std::vector<Pose2> expected;
    const int count = 8 + trial * 4;
    for (const CoarsePlacement& c : ranked) {
      if (static_cast<int>(expected.size()) >= count) break;
      if (std::all_of(expected.begin(), expected.end(),
                      [&](const Pose2& p) { return distinct_modes(c.pose, p, config); }))
        expected.push_back(c.pose);
    }
    const std::vector<Pose2> got = distinct_best(all, count, config);
    ASSERT_EQ(got.size(), expected.size()) << "trial " << trial;
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].x, expected[i].x) << "trial " << trial << ", mode " << i;
      EXPECT_EQ(got[i].theta, expected[i].theta) << "trial " << trial << ", mode " << i;
    }
  }
}

}  // namespace
}  // namespace dsswarm
