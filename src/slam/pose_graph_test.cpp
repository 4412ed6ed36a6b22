#include "slam/pose_graph.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "slam/test_graphs.hpp"

namespace dsswarm {
namespace {

using test::drifting_graph;
using test::kNodesPerSubmap;
using test::square;
using test::true_loop;

double end_error(const PoseGraph& g, const std::vector<Pose2>& truth) {
  const Pose2 e = between(between(truth.front(), truth.back()), between(g.nodes.front(), g.nodes.back()));
  return std::hypot(e.x, e.y);
}

double max_error(const PoseGraph& g, const std::vector<Pose2>& truth) {
  double worst = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i)
    worst = std::max(worst, std::hypot(g.nodes[i].x - truth[i].x, g.nodes[i].y - truth[i].y));
  return worst;
}

TEST(PoseGraph, ASquareLoopWithDriftClosesAtTheLoopEdges) {
  const std::vector<Pose2> truth = square();
  PoseGraph g = drifting_graph(truth);
  ASSERT_GT(end_error(g, truth), 0.5);  // the drift: the loop does not close by itself
  const int last = static_cast<int>(truth.size()) - 1;
  for (int node = last - 3; node <= last; ++node) g.constraints.push_back(true_loop(truth, node, 0));
  const OptimizationSummary s = optimize(g, PoseGraphConfig{});
  ASSERT_TRUE(s.usable);
  EXPECT_LT(s.final_cost, s.initial_cost);
  EXPECT_LT(end_error(g, truth), 0.05);
  // The drift is spread over the loop: every node within 0.6 m of the truth
  // (the local measurements themselves are biased), not 2 m off at the end.
  EXPECT_LT(max_error(g, truth), 0.6);
  // The submap held fixed stayed put.
  EXPECT_EQ(g.submaps[0].x, truth.front().x);
  EXPECT_EQ(g.submaps[0].theta, truth.front().theta);
}

TEST(PoseGraph, AWrongLoopEdgeAmongRightOnesIsOutweighedAndStandsOut) {
  const std::vector<Pose2> truth = square();
  const int last = static_cast<int>(truth.size()) - 1;
  PoseGraph right = drifting_graph(truth);
  for (int node = last - 3; node <= last; ++node) right.constraints.push_back(true_loop(truth, node, 0));
  // Mid-way along the third side, a closure to the first submap as if the
  // corridors were the same: 2 m and 20 degrees off the truth.
  PoseGraph wrong = right;
  Constraint bad = true_loop(truth, 50, 1);
  bad.relative = bad.relative * Pose2(2.0, 0.0, 0.35);
  wrong.constraints.push_back(bad);
  PoseGraph least_squares = wrong;
  optimize(right, PoseGraphConfig{});
  optimize(wrong, PoseGraphConfig{});
  PoseGraphConfig no_robust_loss;
  no_robust_loss.loop_huber = 1e9;
  optimize(least_squares, no_robust_loss);
  auto moved = [&](const PoseGraph& g) {
    double m = 0.0;
    for (std::size_t i = 0; i < truth.size(); ++i)
      m = std::max(m, std::hypot(g.nodes[i].x - right.nodes[i].x, g.nodes[i].y - right.nodes[i].y));
    return m;
  };
  // The robust loss keeps the wrong edge from dragging the graph as plain
  // least squares lets it ...
  EXPECT_LT(moved(wrong), 0.4 * moved(least_squares));
  // ... and the wrong edge keeps a residual far beyond any right edge's, so
  // a residual check after optimization finds it.
  const Pose2 e_bad = constraint_error(wrong, wrong.constraints.back());
  double worst_right = 0.0;
  for (std::size_t k = 0; k + 1 < wrong.constraints.size(); ++k)
    if (wrong.constraints[k].kind == Constraint::Kind::loop) {
      const Pose2 e = constraint_error(wrong, wrong.constraints[k]);
      worst_right = std::max(worst_right, std::hypot(e.x, e.y));
    }
  EXPECT_GT(std::hypot(e_bad.x, e_bad.y), 1.0);
  EXPECT_LT(worst_right, 0.1);
}

// Another robot's frame, seen from our nodes at both ends of the drifting
// square as if its map were bent: coupled, those constraints pull our nodes
// too; with foreign_moves_own off our graph is solved on its own constraints
// and only the frame is placed, against our nodes as they are.
TEST(PoseGraph, ForeignConstraintsMoveOurNodesOnlyWhenAllowed) {
  const std::vector<Pose2> truth = test::square();
  PoseGraph base = test::drifting_graph(truth);
  base.frames.push_back(Pose2(1.0, 2.0, 0.3));
  const int last = static_cast<int>(truth.size()) - 1;
  // Node 0 and the last node (the same place) seen at the frame's origin, the last 0.3 m and 2 degrees off.
  base.constraints.push_back({Constraint::Kind::foreign, 0, 0, Pose2(1.0, 2.0, 0.3).inverse() * truth.front()});
  base.constraints.push_back(
      {Constraint::Kind::foreign, 0, last, Pose2(1.3, 2.0, 0.3 + 0.035).inverse() * truth.back()});
  PoseGraph alone = base;
  alone.constraints.resize(alone.constraints.size() - 2);
  alone.frames.clear();
  PoseGraphConfig config;
  ASSERT_TRUE(optimize(alone, config).usable);

  PoseGraph rigid = base, coupled = base;
  config.foreign_moves_own = false;
  ASSERT_TRUE(optimize(rigid, config).usable);
  config.foreign_moves_own = true;
  ASSERT_TRUE(optimize(coupled, config).usable);
  double rigid_moved = 0.0, coupled_moved = 0.0;
  for (std::size_t i = 0; i < alone.nodes.size(); ++i) {
    const auto d = [&](const PoseGraph& g) { return std::hypot(g.nodes[i].x - alone.nodes[i].x, g.nodes[i].y - alone.nodes[i].y); };
    rigid_moved = std::max(rigid_moved, d(rigid));
    coupled_moved = std::max(coupled_moved, d(coupled));
  }
  EXPECT_LT(rigid_moved, 1e-6);
  EXPECT_GT(coupled_moved, 0.05);
  // The frame is placed between what the two nodes say, either way.
  EXPECT_GT(rigid.frames[0].x, 1.0);
  EXPECT_LT(rigid.frames[0].x, 1.3);
}

// Another robot's closure into our submap places its frame as ours into its
// submaps would: its node, where it holds it in its frame, at the measured
// pose in our submap.
TEST(PoseGraph, APeerClosurePlacesTheOtherRobotsFrame) {
  PoseGraph g;
  g.submaps = {Pose2(0, 0, 0)};
  g.nodes = {Pose2(1, 0, 0)};
  g.constraints.push_back({Constraint::Kind::local, 0, 0, Pose2(1, 0, 0)});
  g.frames = {Pose2(0, 0, 0)};  // a guess
  const Pose2 node(2, 1, 0.5), measured(4, -1, 1.0);
  g.peer.push_back({0, 0, node, measured});
  ASSERT_TRUE(optimize(g, PoseGraphConfig{}).usable);
  const Pose2 want = measured * node.inverse();
  EXPECT_NEAR(g.frames[0].x, want.x, 1e-6);
  EXPECT_NEAR(g.frames[0].y, want.y, 1e-6);
  EXPECT_NEAR(normalize_angle(g.frames[0].theta - want.theta), 0.0, 1e-6);
}

// Peer closures that disagree with our own graph move our submaps only when
// foreign constraints may (graph.foreign_moves_own).
TEST(PoseGraph, PeerClosuresMoveOurSubmapsOnlyWhenAllowed) {
  PoseGraph base;
  base.submaps = {Pose2(0, 0, 0), Pose2(2, 0, 0)};
  base.nodes = {Pose2(1, 0, 0), Pose2(3, 0, 0)};
  base.constraints = {{Constraint::Kind::local, 0, 0, Pose2(1, 0, 0)},
                      {Constraint::Kind::local, 1, 1, Pose2(1, 0, 0)},
                      {Constraint::Kind::local, 0, 1, Pose2(3, 0, 0)}};
  base.frames = {Pose2(0, 0, 0)};
  // The frame 0.5 m along x by submap 0; by submap 1, 0.3 m off to the side.
  base.peer = {{0, 0, Pose2(0, 0, 0), Pose2(0.5, 0, 0)}, {1, 0, Pose2(1, 0, 0), Pose2(0, 0.3, 0)}};
  PoseGraphConfig config;
  config.foreign_moves_own = false;
  PoseGraph rigid = base;
  ASSERT_TRUE(optimize(rigid, config).usable);
  EXPECT_NEAR(rigid.submaps[1].x, 2.0, 1e-9);
  EXPECT_NEAR(rigid.submaps[1].y, 0.0, 1e-9);
  EXPECT_GT(rigid.frames[0].x, 0.5);  // placed between what the two closures say
  EXPECT_LT(rigid.frames[0].x, 1.0);
  config.foreign_moves_own = true;
  PoseGraph coupled = base;
  ASSERT_TRUE(optimize(coupled, config).usable);
  EXPECT_LT(coupled.submaps[1].y, -0.01);  // bent towards the other robot's map
}

TEST(PoseGraph, ConstraintErrorIsZeroWhereTheMeasurementHolds) {
  PoseGraph g;
  g.nodes = {Pose2(1, 2, 0.3), Pose2(2, 2.5, 0.6)};
  g.submaps = {Pose2(0.5, 1, 0.1)};
  const Constraint local{Constraint::Kind::local, 0, 0, between(g.submaps[0], g.nodes[0])};
  const Constraint loop{Constraint::Kind::loop, 0, 1, between(g.submaps[0], g.nodes[1]) * Pose2(0.1, 0, 0)};
  EXPECT_NEAR(std::hypot(constraint_error(g, local).x, constraint_error(g, local).y), 0.0, 1e-12);
  EXPECT_NEAR(constraint_error(g, loop).x, -0.1, 1e-12);
  // An empty graph is left alone.
  PoseGraph empty;
  EXPECT_FALSE(optimize(empty, PoseGraphConfig{}).usable);
}

}  // namespace
}  // namespace dsswarm
