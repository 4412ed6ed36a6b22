#include "slam/submaps.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "grid/map_combine.hpp"

namespace dsswarm {
namespace {

// A scan of a 4 m circle of wall around the robot.
LaserScan ring_scan() {
  LaserScan s;
  s.angle_min = -std::numbers::pi;
  s.angle_increment = 2.0 * std::numbers::pi / 180.0;
  s.range_max = 30.0;
  s.ranges.assign(180, 4.0f);
  return s;
}

Pose2 pose_at(int k) { return Pose2(0.1 * k, 0.02 * k, 0.01 * k); }

TEST(Submaps, EveryScanGoesIntoExactlyOneSubmapAndFullOnesAreFinished) {
  SubmapConfig config;
  config.max_scans = 10;
  Submaps submaps(MapConfig{}, config, InsertConfig{});
  const LaserScan scan = ring_scan();
  const std::vector<ScanPoint> points = scan_to_points(scan);
  std::vector<int> went_into;
  for (int k = 0; k < 35; ++k) went_into.push_back(*submaps.insert(pose_at(k), scan, points));
  ASSERT_EQ(submaps.finished().size(), 3u);
  EXPECT_EQ(submaps.current().scans, 5);
  int total = submaps.current().scans;
  for (std::size_t i = 0; i < submaps.finished().size(); ++i) {
    const Submap& s = *submaps.finished()[i];
    EXPECT_EQ(s.id, static_cast<int>(i));
    EXPECT_TRUE(s.finished);
    EXPECT_EQ(s.scans, 10);
    // Anchored at its first scan.
    EXPECT_EQ(s.anchor.x, pose_at(10 * static_cast<int>(i)).x);
    total += s.scans;
  }
  EXPECT_EQ(total, 35);
  EXPECT_EQ(submaps.scans_inserted(), 35u);
  for (int k = 0; k < 35; ++k) EXPECT_EQ(went_into[static_cast<std::size_t>(k)], k / 10);
}

TEST(Submaps, TravelFinishesASubmapToo) {
  SubmapConfig config;
  config.max_travel = 1.0;  // 10 steps of 0.102 m
  Submaps submaps(MapConfig{}, config, InsertConfig{});
  const LaserScan scan = ring_scan();
  const std::vector<ScanPoint> points = scan_to_points(scan);
  for (int k = 0; k < 12; ++k) submaps.insert(pose_at(k), scan, points);
  ASSERT_EQ(submaps.finished().size(), 1u);
  EXPECT_GE(submaps.finished().front()->travel, 1.0);
  EXPECT_EQ(submaps.finished().front()->scans, 11);
}

TEST(Submaps, TheLocalMapIsThePreviousSubmapWithTheCurrentOneUntilItIsHalfFull) {
  SubmapConfig config;
  config.max_scans = 10;
  Submaps submaps(MapConfig{}, config, InsertConfig{});
  const LaserScan scan = ring_scan();
  const std::vector<ScanPoint> points = scan_to_points(scan);
  for (int k = 0; k < 12; ++k) submaps.insert(pose_at(k), scan, points);
  // Submap 0 finished, submap 1 holds 2 scans: local = submap 0 ⊕ submap 1.
  MultiResMap expected = submaps.finished().front()->frozen.thaw(MapConfig{});
  combine_aligned(expected, submaps.current().map);
  // Where the first scan saw the wall straight ahead: only submap 0 knows it.
  const CellIndex wall = expected.finest().cell_of(pose_at(0) * Eigen::Vector2d(4.0, 0.0));
  EXPECT_GT(submaps.local_map().finest().at(wall).occupied, 0.3f);
  EXPECT_EQ(submaps.current().map.finest().at(wall).occupied, 0.0f);
  EXPECT_NEAR(submaps.local_map().finest().at(wall).occupied, expected.finest().at(wall).occupied, 0.02);
  for (int k = 12; k < 15; ++k) submaps.insert(pose_at(k), scan, points);
  // Half full: local SLAM matches against the current submap alone.
  EXPECT_EQ(&submaps.local_map(), &submaps.current().map);
}

TEST(Submaps, TheGlobalMapIsTheCombinationOfTheSubmapsAtTheirPoses) {
  SubmapConfig config;
  config.max_scans = 10;
  Submaps submaps(MapConfig{}, config, InsertConfig{});
  const LaserScan scan = ring_scan();
  const std::vector<ScanPoint> points = scan_to_points(scan);
  for (int k = 0; k < 25; ++k) submaps.insert(pose_at(k), scan, points);
  // Each submap moved as a loop closure might move it.
  auto pose_of = [](int id) { return Pose2(0.03 * id, -0.02 * id, 0.01 * id); };
  const MultiResMap global = combine_submaps(MapConfig{}, submaps.all(), pose_of);
  MultiResMap expected;
  for (const Submap* s : submaps.all())
    combine_into(expected, s->finished ? s->frozen.thaw(MapConfig{}) : s->map, pose_of(s->id));
  for (int l = 0; l < global.levels(); ++l) {
    EXPECT_EQ(global.level(l).tiles_allocated(), expected.level(l).tiles_allocated());
    expected.level(l).for_each_tile([&](CellIndex origin, const PackedMass* cells) {
      for (int i = 0; i < DsGrid::kTileCells; i += 7) {
        const DsMass g = global.level(l).at(DsGrid::tile_cell(origin, i));
        // Identity poses are combined cell by cell, others resampled: equal
        // but for the bilinear weights' rounding.
        ASSERT_NEAR(g.occupied, cells[i].mass().occupied, 1e-5f);
        ASSERT_NEAR(g.free, cells[i].mass().free, 1e-5f);
      }
    });
  }
}

// An executor that runs each job when waited for, after the caller's own
// work: the order two threads could take.
class DeferredExecutor final : public Executor {
 public:
  std::uint64_t submit(std::function<void()> job) override {
    jobs_.push_back(std::move(job));
    return jobs_.size();
  }
  void wait_for(std::uint64_t ticket) override {
    for (; done_ < ticket; ++done_) jobs_[done_]();
  }
  void wait() override { wait_for(jobs_.size()); }

 private:
  std::vector<std::function<void()>> jobs_;
  std::size_t done_ = 0;
};

TEST(Submaps, TheGlobalMapComposedInTwoBandsIsTheSameToTheBit) {
  SubmapConfig config;
  config.max_scans = 10;
  Submaps submaps(MapConfig{}, config, InsertConfig{});
  const LaserScan scan = ring_scan();
  const std::vector<ScanPoint> points = scan_to_points(scan);
  for (int k = 0; k < 45; ++k) submaps.insert(Pose2(0.1 * k, 0.3 * k, 0.01 * k), scan, points);
  auto pose_of = [](int id) { return id == 0 ? Pose2() : Pose2(0.03 * id, -0.02 * id, 0.01 * id); };
  const MultiResMap one = combine_submaps(MapConfig{}, submaps.all(), pose_of);
  DeferredExecutor helper;
  const MultiResMap two = combine_submaps(MapConfig{}, submaps.all(), pose_of, &helper);
  for (int l = 0; l < one.levels(); ++l) {
    ASSERT_EQ(two.level(l).tiles_allocated(), one.level(l).tiles_allocated());
    one.level(l).for_each_tile([&](CellIndex origin, const PackedMass* cells) {
      for (int i = 0; i < DsGrid::kTileCells; ++i) {
        const PackedMass m = two.level(l).packed_at(DsGrid::tile_cell(origin, i));
        ASSERT_EQ(m.occupied, cells[i].occupied);
        ASSERT_EQ(m.free, cells[i].free);
      }
    });
  }
  // Both bands did some of it: the map spans 13 m along y, split at a submap's start.
  CellIndex lo, hi;
  one.finest().bounds(lo, hi);
  EXPECT_GT((hi.y - lo.y) * 0.05, 10.0);
}

TEST(Submaps, FreezingLeavesOnlyCompactSubmapsAndResumingGoesOn) {
  SubmapConfig config;
  config.max_scans = 10;
  Submaps submaps(MapConfig{}, config, InsertConfig{});
  const LaserScan scan = ring_scan();
  const std::vector<ScanPoint> points = scan_to_points(scan);
  for (int k = 0; k < 14; ++k) submaps.insert(pose_at(k), scan, points);
  const std::size_t live = submaps.memory_bytes();
  submaps.freeze();
  EXPECT_EQ(submaps.finished().size(), 2u);  // the growing one was finished
  EXPECT_EQ(submaps.current().scans, 0);
  EXPECT_LT(submaps.memory_bytes() * 4, live);
  submaps.resume();
  EXPECT_GT(submaps.local_map().finest().tiles_allocated(), 0u);
  EXPECT_EQ(*submaps.insert(pose_at(14), scan, points), 2);
}

TEST(Submaps, ARobotThatDidNotMoveEnoughInsertsNothing) {
  InsertConfig insert;
  insert.min_travel = 0.5;
  insert.min_rotation = 0.5;
  Submaps submaps(MapConfig{}, SubmapConfig{}, insert);
  const LaserScan scan = ring_scan();
  const std::vector<ScanPoint> points = scan_to_points(scan);
  EXPECT_TRUE(submaps.insert(Pose2(), scan, points));
  EXPECT_FALSE(submaps.insert(Pose2(0.1, 0, 0), scan, points));
  EXPECT_TRUE(submaps.insert(Pose2(0.6, 0, 0), scan, points));
  EXPECT_EQ(submaps.scans_inserted(), 2u);
}

}  // namespace
}  // namespace dsswarm
