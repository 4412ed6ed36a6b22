#pragma once
// Pose graphs with a known truth for the pose-graph and loop-closing tests.
#include <numbers>
#include <vector>

#include "slam/pose_graph.hpp"

namespace dsswarm::test {

// A 10 m square driven once, a node every 0.5 m (turning in place at the
// corners), a submap every 10 nodes anchored at its first node.
inline std::vector<Pose2> square() {
  std::vector<Pose2> truth;
  Pose2 p;
  for (int side = 0; side < 4; ++side) {
    for (int k = 0; k < 20; ++k) {
      truth.push_back(p);
      p = p * Pose2(0.5, 0.0, 0.0);
    }
    p = p * Pose2(0.0, 0.0, std::numbers::pi / 2);
  }
  truth.push_back(p);  // back at the start
  return truth;
}

constexpr int kNodesPerSubmap = 10;

// Local SLAM's view: every step measured with a heading error of 0.11
// degrees, integrated into a drifting local frame; local constraints from it
// (each node in its submap, the first two also in the submap before), the
// global poses initialized to it.
inline PoseGraph drifting_graph(const std::vector<Pose2>& truth) {
  PoseGraph g;
  Pose2 local = truth.front();
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (i > 0) local = local * between(truth[i - 1], truth[i]) * Pose2(0.0, 0.0, 0.002);
    g.nodes.push_back(local);
    if (i % kNodesPerSubmap == 0) g.submaps.push_back(local);
    const int s = static_cast<int>(i) / kNodesPerSubmap, node = static_cast<int>(i);
    g.constraints.push_back({Constraint::Kind::local, s, node, between(g.submaps.back(), local)});
    if (s > 0 && i % kNodesPerSubmap < 2)
      g.constraints.push_back({Constraint::Kind::local, s - 1, node, between(g.submaps[g.submaps.size() - 2], local)});
  }
  return g;
}

// A loop closure measured exactly: node `node` in submap `submap`, from the truth.
inline Constraint true_loop(const std::vector<Pose2>& truth, int node, int submap) {
  return {Constraint::Kind::loop, submap, node,
          between(truth[static_cast<std::size_t>(submap * kNodesPerSubmap)], truth[static_cast<std::size_t>(node)])};
}

}  // namespace dsswarm::test
