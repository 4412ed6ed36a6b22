// Another robot's map in this robot's pose graph: an encounter whose heading
// is a little off is corrected by loop closures into the other robot's
// submaps, where the two robots' paths overlap.
#include <gtest/gtest.h>

#include <numbers>

#include "eval/ate.hpp"
#include "sim/test_laps.hpp"
#include "slam/slam.hpp"

namespace dsswarm {
namespace {

constexpr int kFrame = 7;  // the caller's id for robot B

struct Robots {
  SimulatedRun a = test::lap(0, 1), b = test::lap(2, 2);
  // Each map's frame is where its robot started (odometry starts at identity).
  Pose2 b_in_a = between(a.ground_truth.front().second, b.ground_truth.front().second);
};

struct Outcome {
  std::size_t foreign_accepted = 0;
  double b_error_met = 0.0;  // mean, m: B's trajectory placed in A's frame as the encounter placed it, against the truth
  double b_error = 0.0;      // the same as A ends up placing B's frame
  double a_error = 0.0;      // mean, m: A's own trajectory, against the truth
};

// Mean distance between `poses` (placed by `frame`) and the truth, seen from `start` (a map frame's origin).
double mean_error(const SimulatedRun& run, const std::vector<Pose2>& poses, const Pose2& frame, const Pose2& start) {
  double sum = 0.0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Pose2 est = frame * poses[i], truth = between(start, run.ground_truth[i].second);
    sum += std::hypot(est.x - truth.x, est.y - truth.y);
  }
  return sum / static_cast<double>(poses.size());
}

// Robot A maps its lap; at its scan `meet` it meets B, whose whole map it
// then holds, and the encounter places B's frame `heading_error` off about A.
Outcome map_with_b(const Robots& r, const std::vector<ForeignPiece>& b_pieces, const std::vector<Pose2>& b_poses,
                   double heading_error) {
  Slam a(with_loop_closure());
  const Pose2 start_a = r.a.ground_truth.front().second;
  Outcome out;
  constexpr std::size_t meet = 60;
  for (std::size_t i = 0; i < r.a.log.scans.size(); ++i) {
    const SlamStep step = a.process(r.a.log.scans[i]);
    if (i != meet) continue;
    // What the encounter saw: B's frame turned by heading_error about where A stands.
    const Pose2 here = between(start_a, r.a.ground_truth[i].second);
    const Pose2 seen = here * Pose2(0.0, 0.0, heading_error) * between(here, r.b_in_a);
    a.set_foreign_map(kFrame, seen, b_pieces);
    a.add_encounter(kFrame, i, step.pose, seen);
    out.b_error_met = mean_error(r.b, b_poses, seen, start_a);
  }
  a.finish();
  out.foreign_accepted = a.loop_closer().stats().foreign_accepted;
  out.b_error = mean_error(r.b, b_poses, *a.foreign_frame(kFrame), start_a);
  out.a_error = mean_error(r.a, a.trajectory(), Pose2(), start_a);
  return out;
}

TEST(ForeignMaps, AnEncounterTurnedByOneDegreeIsStraightenedByClosuresIntoTheOtherRobotsSubmaps) {
  const Robots r;
  Slam b(with_loop_closure());
  for (const LaserScan& s : r.b.log.scans) b.process(s);
  b.finish();
  const std::vector<ForeignPiece> pieces = b.finished_pieces();
  ASSERT_GT(pieces.size(), 4u);
  const double one_degree = std::numbers::pi / 180.0;

  const Outcome o = map_with_b(r, pieces, b.trajectory(), one_degree);
  // Where A met B, one degree is a few centimetres; levered over the ring it is decimetres.
  EXPECT_GT(o.b_error_met, 0.2);
  // Closures into B's submaps all along the ring put B's map where it is:
  // within A's own error of the truth plus B's (the shape B's trajectory has,
  // which no placement of it can straighten), and far from the error as met.
  Trajectory b_estimate, b_truth;
  const std::vector<Pose2> b_poses = b.trajectory();
  for (std::size_t i = 0; i < b_poses.size(); ++i) {
    b_estimate.push_back({r.b.log.scans[i].timestamp, b_poses[i]});
    b_truth.push_back({r.b.ground_truth[i].first, r.b.ground_truth[i].second});
  }
  const double b_own = evaluate_ate(b_estimate, b_truth).rmse;
  EXPECT_GT(o.foreign_accepted, 10u);
  EXPECT_LT(o.b_error, o.a_error + b_own) << "A's error " << o.a_error << ", B's own " << b_own;
  EXPECT_LT(o.b_error, 0.5 * o.b_error_met);
}

// B's later loop closures moved its scan where the robots met: A's tie
// follows it, so the frame moves by as much, seen from that scan.
TEST(ForeignMaps, AnEncounterFollowsTheOtherRobotsScanWhenItsClosuresMoveIt) {
  const Robots r;
  Slam a(with_loop_closure());
  constexpr std::size_t meet = 60;
  constexpr std::uint64_t kEncounter = 5;
  const Pose2 frame(4.0, -2.0, 0.7), then(3.0, 1.0, 0.2), now(3.2, 0.9, 0.25);  // B's scan, in B's frame
  for (std::size_t i = 0; i < r.a.log.scans.size(); ++i) {
    const SlamStep step = a.process(r.a.log.scans[i]);
    if (i != meet) continue;
    a.set_foreign_map(kFrame, frame, {});
    a.add_encounter(kFrame, i, step.pose, frame, kEncounter);
    EXPECT_FALSE(a.move_encounter(kFrame, kEncounter + 1, then, now));  // not an encounter of ours
    EXPECT_FALSE(a.move_encounter(kFrame + 1, kEncounter, then, now));
  }
  a.finish();
  const Pose2 before = *a.foreign_frame(kFrame);
  EXPECT_TRUE(a.move_encounter(kFrame, kEncounter, then, now));
  EXPECT_FALSE(a.move_encounter(kFrame, kEncounter, then, now));  // once is enough
  a.finish();
  const Pose2 after = *a.foreign_frame(kFrame), want = before * then * now.inverse();
  EXPECT_NEAR(after.x, want.x, 1e-6);
  EXPECT_NEAR(after.y, want.y, 1e-6);
  EXPECT_NEAR(normalize_angle(after.theta - want.theta), 0.0, 1e-6);
  EXPECT_GT(std::hypot(after.x - before.x, after.y - before.y), 0.1);
}

// A piece whose only evidence is cell (3, 4).
std::shared_ptr<const FrozenMap> one_cell_piece(const MapConfig& config) {
  MultiResMap map(config);
  map.mutable_level(0).set({3, 4}, {0.6f, 0.1f});
  return std::make_shared<const FrozenMap>(map);
}

TEST(ForeignMaps, PiecesAlreadyHeldKeepTheirEvidenceAndTakeTheNewPose) {
  const MapConfig config;
  const auto frozen = one_cell_piece(config);
  ForeignMaps maps(config);
  EXPECT_EQ(maps.set(1, Pose2(1, 0, 0), {{0, Pose2(), frozen}, {1, Pose2(2, 0, 0), frozen}}).size(), 2u);
  // Robot 1 closed a loop: piece 1 moved; piece 2 is new.
  const std::vector<std::size_t> added = maps.set(1, Pose2(1, 0, 0), {{1, Pose2(2.5, 0, 0.1), frozen}, {2, Pose2(), frozen}});
  ASSERT_EQ(added.size(), 1u);
  EXPECT_EQ(maps.pieces()[added[0]].piece.id, 2);
  EXPECT_DOUBLE_EQ(maps.pieces()[1].piece.pose.x, 2.5);
  EXPECT_NEAR(maps.pieces()[0].centre.x(), 1.6, 1e-9);  // the tile holding cell (3, 4): [0, 3.2) m
  // Piece 0 is no longer in robot 1's list (it resumed, its saved map now one
  // piece): held, not searched. Sent again, it is current again.
  EXPECT_FALSE(maps.pieces()[0].current);
  EXPECT_TRUE(maps.pieces()[1].current);
  EXPECT_TRUE(maps.pieces()[2].current);
  maps.set(1, Pose2(1, 0, 0), {{0, Pose2(), frozen}, {1, Pose2(2.5, 0, 0.1), frozen}, {2, Pose2(), frozen}});
  EXPECT_TRUE(maps.pieces()[0].current);
  // Until an encounter ties it into the graph, the frame takes the caller's pose.
  maps.set(1, Pose2(3, 0, 0), {});
  EXPECT_DOUBLE_EQ(maps.frame_pose(1).x, 3.0);
  maps.encounter(1, 0, Pose2(), Pose2(4, 0, 0));
  maps.set(1, Pose2(5, 0, 0), {});
  EXPECT_DOUBLE_EQ(maps.frame_pose(1).x, 4.0);
}

// Robot 1 closed a loop after we had closed into one of its submaps, and its
// next snapshot moved that submap: our closure moves with it, as if measured
// in the submap where it lies now; closures into other pieces, and the
// encounter (in no piece), stay.
TEST(ForeignMaps, AClosureIntoAPieceMovesWithThePiece) {
  const MapConfig config;
  const auto frozen = one_cell_piece(config);
  ForeignMaps maps(config);
  const Pose2 before(2.0, 1.0, 0.3), after(2.2, 0.9, 0.33);
  maps.set(1, Pose2(), {{0, Pose2(), frozen}, {1, before, frozen}});
  const Pose2 in_cells(0.5, -0.25, 0.1);  // the node where the search placed it in piece 1's cells
  std::vector<Constraint> constraints{maps.encounter(1, 3, Pose2(1, 1, 0), Pose2()),
                                      {Constraint::Kind::foreign, 0, 5, in_cells, 0, Pose2()},
                                      {Constraint::Kind::foreign, 0, 6, before * in_cells, 1, before}};
  const std::vector<Constraint> measured = constraints;
  follow_pieces(constraints, maps.pieces());  // nothing moved yet
  for (std::size_t i = 0; i < constraints.size(); ++i) EXPECT_EQ(constraints[i].relative.x, measured[i].relative.x);

  maps.set(1, Pose2(), {{0, Pose2(), frozen}, {1, after, frozen}});
  follow_pieces(constraints, maps.pieces());
  const Pose2 want = after * in_cells;
  EXPECT_NEAR(constraints[2].relative.x, want.x, 1e-12);
  EXPECT_NEAR(constraints[2].relative.y, want.y, 1e-12);
  EXPECT_NEAR(constraints[2].relative.theta, want.theta, 1e-12);
  EXPECT_EQ(constraints[2].piece_pose.x, after.x);
  for (std::size_t i : {0u, 1u}) {
    EXPECT_EQ(constraints[i].relative.x, measured[i].relative.x);
    EXPECT_EQ(constraints[i].relative.theta, measured[i].relative.theta);
  }
}

}  // namespace
}  // namespace dsswarm
