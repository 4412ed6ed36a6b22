#include "slam/loop_round.hpp"

#include <gtest/gtest.h>

#include "slam/test_graphs.hpp"

namespace dsswarm {
namespace {

// A round over the drifting square with no searches: only `pending`
// candidates to confirm, optimize and check.
Round round_with(const std::vector<Pose2>& truth, const std::vector<Constraint>& candidates) {
  Round round;
  RoundInput& in = round.in;
  in.graph = test::drifting_graph(truth);
  in.node_local = in.graph.nodes;  // the round's estimates: local SLAM's, nothing optimized yet
  for (std::size_t i = 0; i < truth.size(); ++i) {
    in.node_submap.push_back(static_cast<int>(i) / test::kNodesPerSubmap);
    in.node_travel.push_back(0.5 * static_cast<double>(i));
  }
  for (std::size_t s = 0; s < in.graph.submaps.size(); ++s) {
    RoundInput::SubmapInfo info;
    info.anchor = in.graph.submaps[s];
    for (int n = 0; n < test::kNodesPerSubmap; ++n) info.nodes.push_back(static_cast<int>(s) * test::kNodesPerSubmap + n);
    info.travel_end = 0.5 * static_cast<double>((s + 1) * test::kNodesPerSubmap);
    in.submaps.push_back(info);
  }
  for (const Constraint& c : candidates) {
    LoopCandidate k;
    k.node = c.node;
    k.submap = c.submap;
    k.relative = c.relative;
    round.base.pending.push_back({k, 0});
  }
  return round;
}

bool accepted(const RoundOutput& out, int node) {
  for (const LoopCandidate& c : out.accepted)
    if (c.node == node) return true;
  return false;
}

TEST(LoopRound, RightClosuresThatAgreeAreAcceptedAndCloseTheLoop) {
  const std::vector<Pose2> truth = test::square();
  const int last = static_cast<int>(truth.size()) - 1;
  Round round = round_with(truth, {test::true_loop(truth, last - 2, 0), test::true_loop(truth, last, 0)});
  run_round(round, LoopClosureConfig{}, PointWeightConfig{}, 1);
  EXPECT_TRUE(accepted(round.out, last - 2));
  EXPECT_TRUE(accepted(round.out, last));
  ASSERT_TRUE(round.out.optimized);
  const Pose2 e = between(truth.back(), round.out.graph.nodes.back());
  EXPECT_LT(std::hypot(e.x, e.y), 0.05);
}

TEST(LoopRound, ALoneClosureWaitsForAPartnerAndThenExpires) {
  const std::vector<Pose2> truth = test::square();
  const int last = static_cast<int>(truth.size()) - 1;
  LoopClosureConfig config;
  config.pending_rounds = 1;
  Round round = round_with(truth, {test::true_loop(truth, last, 0)});
  run_round(round, config, PointWeightConfig{}, 1);
  EXPECT_TRUE(round.out.accepted.empty());
  ASSERT_EQ(round.out.pending.size(), 1u);
  Round next = round_with(truth, {});
  next.base = round.out.state;  // the round after it starts where it ended
  run_round(next, config, PointWeightConfig{}, 1);
  EXPECT_TRUE(next.out.pending.empty());
  EXPECT_EQ(next.out.stats.rejected_inconsistent, 1u);
}

TEST(LoopRound, WrongClosuresThatAgreeWithEachOtherAreDroppedByTheOptimizedGraph) {
  // Right closures at the end of the loop, and two wrong ones mid-way along
  // the third side that agree with each other (as two scans of a repeating
  // corridor would): 2 m and 20 degrees off the truth into submap 1.
  const std::vector<Pose2> truth = test::square();
  const int last = static_cast<int>(truth.size()) - 1;
  std::vector<Constraint> candidates{test::true_loop(truth, last - 2, 0), test::true_loop(truth, last, 0)};
  for (int node : {50, 52}) {
    Constraint bad = test::true_loop(truth, node, 1);
    bad.relative = Pose2(2.0, 0.0, 0.35) * bad.relative;
    candidates.push_back(bad);
  }
  Round round = round_with(truth, candidates);
  run_round(round, LoopClosureConfig{}, PointWeightConfig{}, 1);
  EXPECT_TRUE(accepted(round.out, last - 2));
  EXPECT_TRUE(accepted(round.out, last));
  EXPECT_FALSE(accepted(round.out, 50));
  EXPECT_FALSE(accepted(round.out, 52));
  EXPECT_EQ(round.out.stats.rejected_residual, 2u);
  const Pose2 e = between(truth.back(), round.out.graph.nodes.back());
  EXPECT_LT(std::hypot(e.x, e.y), 0.05);
}

}  // namespace
}  // namespace dsswarm
