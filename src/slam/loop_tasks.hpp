#pragma once
// The searches a loop-closing round runs (loop_round.cpp): each new node
// against the finished submaps and other robots' pieces near it, with the
// window and prior of each. Private to the round.
#include <vector>

#include "slam/loop_round.hpp"

namespace dsswarm::round_detail {

// What a search looks in: one of our finished submaps, or another robot's piece.
struct Target {
  bool foreign = false;
  int index = 0;  // into in.submaps, or into in.foreign
  auto operator<=>(const Target&) const = default;
};

struct Task {
  int node;
  Target target;
  SearchWindow window;
  const CompactScan* points;
  Pose2 prior;  // the node's estimated pose in the target's cells
};

// Every search of the round, target by target.
std::vector<Task> tasks_for(const RoundInput& in, const LoopClosureConfig& config);

}  // namespace dsswarm::round_detail
