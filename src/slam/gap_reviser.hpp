#pragma once
// Better poses for the scans the filter dropped, once the next scan is
// matched: a dropped scan's pose is at first the motion prediction from the
// last matched pose; the match after the gap tells how far that prediction
// was off, and the correction is spread over the gap instead of landing at
// its end (SlamConfig::revise_dropped).
#include <cstddef>
#include <vector>

#include "geometry/pose2.hpp"

namespace dsswarm {

// A better pose for an earlier scan, found after the fact.
struct PoseRevision {
  std::size_t index = 0;  // the scan's position in process() order, from 0
  Pose2 pose;
};

class GapReviser {
 public:
  // A dropped scan with its predicted pose; `last_kept` is the pose of the
  // scan kept before it (where the prediction started).
  void note_dropped(std::size_t index, const Pose2& predicted, const Pose2& last_kept);
  // Revised poses of the gap, oldest first, for the scan that ends it,
  // matched at `matched` from the prediction `prior`.
  std::vector<PoseRevision> revise(const Pose2& matched, const Pose2& prior) const;
  bool empty() const { return gap_.empty(); }
  void clear() { gap_.clear(); }

 private:
  std::vector<PoseRevision> gap_;  // dropped scans since the last kept one, predicted poses
  Pose2 gap_start_;                // the pose of that kept scan
};

}  // namespace dsswarm
