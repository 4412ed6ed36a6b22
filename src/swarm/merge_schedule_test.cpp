#include "swarm/merge_schedule.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "grid/test_cells.hpp"

namespace dsswarm {
namespace {

std::vector<ScanPoint> wall_ahead() {
  std::vector<ScanPoint> points;
  for (int k = -10; k <= 10; ++k) points.push_back({2.0f, 0.1f * static_cast<float>(k), 1.0f});
  return points;
}

MergeSchedule::Job job_at(std::size_t version) {
  return {std::make_shared<const MultiResMap>(), version, {}};
}

TEST(MergeSchedule, AMergeIsDueTheDelayAfterItsScanNotBefore) {
  MergeSchedule s(2.0);
  s.add(job_at(0), 10.0, 4);
  EXPECT_FALSE(s.take_due(11.9, true));
  const std::optional<MergeSchedule::Due> due = s.take_due(12.0, true);
  ASSERT_TRUE(due);
  EXPECT_EQ(due->encounters, std::vector<std::uint64_t>{4});
  EXPECT_FALSE(due->late);
  EXPECT_TRUE(s.empty());
  s.add(job_at(0), 20.0, 5);
  EXPECT_TRUE(s.take_due(3.0, true));  // the log's time went back: not held until 22 s come again
}

// A robot process takes only what its composer finished; a merge not ready
// when its scan came is taken later, and says so.
TEST(MergeSchedule, AMergeNotComposedByItsScanIsTakenWhenReadyAndCountedLate) {
  MergeSchedule s(1.0);
  s.add(job_at(0), 5.0, 9);
  EXPECT_FALSE(s.take_due(6.5, false));
  const std::optional<MergeSchedule::Claimed> c = s.claim();
  ASSERT_TRUE(c);
  EXPECT_EQ(c->encounter, 9u);
  EXPECT_FALSE(s.claim());  // one composer per job
  s.composed(c->ticket, MultiResMap());
  const std::optional<MergeSchedule::Due> due = s.take_due(6.6, false);
  ASSERT_TRUE(due);
  EXPECT_TRUE(due->late);
}

// Two merges due by the same scan: the newer holds the older's layers, so
// only it is installed, for both encounters.
TEST(MergeSchedule, TheNewestDueMergeStandsForTheOlderOnes) {
  MergeSchedule s(1.0);
  s.add(job_at(0), 1.0, 1);
  s.add(job_at(0), 1.5, 2);
  s.add(job_at(0), 3.0, 3);
  const std::optional<MergeSchedule::Due> due = s.take_due(3.2, true);
  ASSERT_TRUE(due);
  EXPECT_EQ(due->encounters, (std::vector<std::uint64_t>{1, 2}));
  EXPECT_FALSE(s.empty());  // encounter 3's is not due yet
}

// The scans inserted after the job's own map are replayed into the merged
// map; those in it already are not (counted once). Scans older than the
// delay that no job needs are let go.
TEST(MergeSchedule, ReplaysExactlyTheScansAfterTheJobsOwnMapAndKeepsNoMore) {
  MergeSchedule s(1.0);
  const Pose2 laser;
  for (std::size_t v = 1; v <= 30; ++v) s.inserted(v, 0.1 * static_cast<double>(v), Pose2{0.05 * static_cast<double>(v), 0, 0}, laser, wall_ahead());
  EXPECT_FALSE(s.replays_from(5, 30));   // 2.5 s ago: let go
  EXPECT_TRUE(s.replays_from(25, 30));   // 0.5 s ago
  EXPECT_TRUE(s.replays_from(30, 30));   // nothing to replay
  MultiResMap own;
  for (std::size_t v = 1; v <= 25; ++v) own.insert_scan(Pose2{0.05 * static_cast<double>(v), 0, 0}, laser, wall_ahead());
  MultiResMap expected = own;
  for (std::size_t v = 26; v <= 30; ++v) expected.insert_scan(Pose2{0.05 * static_cast<double>(v), 0, 0}, laser, wall_ahead());
  s.add({std::make_shared<const MultiResMap>(own), 25, {}}, 2.5, 1);
  const std::optional<MergeSchedule::Due> due = s.take_due(std::numeric_limits<double>::infinity(), true);
  ASSERT_TRUE(due);
  for (int level = 0; level < expected.levels(); ++level)
    EXPECT_EQ(test::largest_difference(expected.level(level), due->working.level(level)), 0.0) << "level " << level;
}

}  // namespace
}  // namespace dsswarm
