#pragma once
// Two robots are near each other: find the transform between their map
// frames, and decide whether it is trustworthy enough to merge on.
//
// Each robot places the other's current scan in its own map (relative_pose),
// giving two independent estimates of the same transform. It is accepted only
// when (1) each placement lands mostly on mapped space and fits it, (2) each
// placement clearly beats the best alternative placement, (3) the two
// directions agree (and, with reject_bent_maps, (4) fitting both maps as wholes
// keeps the transform within that same tolerance). A wrong merge corrupts a
// map for good; a rejected one costs only a wait for the next encounter.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "grid/multires_map.hpp"
#include "sensor/scan_points.hpp"
#include "swarm/relative_pose.hpp"

namespace dsswarm {

struct EncounterConfig {
  RelativePoseConfig locate;
  double min_known_fraction = 0.5;  // share of the foreign scan that must land on mapped cells
  double min_inlier_ratio = 0.6;    // share of those that must land on obstacles
  double min_same_side = 0.8;       // share of those obstacles seen from the same side (same_side_ratio)
  double max_runner_up_ratio = 0.9; // the best alternative must score below this share of the best
  double agree_xy = 0.08;           // m: the two directions' estimates of a robot's position
  double agree_theta = 0.0175;      // rad (1°)
  // When the wide refinement moves the transform beyond agree_xy/agree_theta
  // the maps disagree with each other (at least one is bent between the
  // meeting point and its far parts). Off: merge on the estimate where the
  // robots met, which is right locally. On: reject and wait — in simulation
  // three of the four merges it removed (50 runs) were 6–8 cm off the maps as
  // wholes, but on real logs without loop closure it refuses most merges
  // between large maps.
  bool reject_bent_maps = false;
  // With loop closure on, the wide fit moves no transform (closures into the
  // other robot's submaps line the maps up); it only settles two verified
  // placements that disagree: when each one's wide fit lands within
  // agree_xy / agree_theta of the other's, the maps as wholes agree where
  // one scan could not (the agent sets this from loop_closure.enabled).
  bool wide_fit_settles_only = false;

  void validate() const;  // throws ConfigError naming the field
};

// What one robot contributes: the map it localizes in, its current scan
// (robot base frame) and its pose in its own map frame.
struct EncounterView {
  const MultiResMap* map = nullptr;  // the map it localizes in
  std::vector<ScanPoint> points;
  Pose2 pose;
  // Obstacles of its own map around it, in its base frame (surroundings_points):
  // the other side could cut them from the snapshot it receives; sent
  // ready-made they cost no more than the scan.
  std::vector<ScanPoint> surroundings;
  // The same out to merge_surroundings_radius, for the final transform.
  std::vector<ScanPoint> wide_surroundings;
  std::size_t scan_index = 0;  // the scan's position in the robot's process() order
  // With loop closure on: the robot's unfinished submaps, where its map
  // and what it sees now agree even before a loop has closed; the peer is
  // placed here too (RelativePoseConfig::place_in_recent_submaps).
  std::shared_ptr<const MultiResMap> recent_map{};
};

struct EncounterEstimate {
  bool accepted = false;
  std::string reason;      // why it was rejected ("" when accepted)
  Pose2 b_frame_in_a;      // pose of B's map frame in A's map frame (valid when accepted)
  Pose2 b_frame_in_a_near; // the same from the placements before the wide refinement
  RelativePoseResult a_locates_b;  // B's robot placed in A's map
  RelativePoseResult b_locates_a;  // A's robot placed in B's map
  double disagreement_xy = 0.0;    // m, between the two directions' placements of B
  double disagreement_theta = 0.0; // rad
  // Each placement passed its own checks (known, inliers, same side, runner-up);
  // then only the directions' disagreement can have turned the encounter down.
  bool placements_verified = false;
  Pose2 b_frame_by_a, b_frame_by_b;  // each direction's estimate of B's frame in A's
  // How far the wide refinement moved the accepted estimate, at B's position;
  // beyond agree_xy / agree_theta the near estimate stands (or, with
  // reject_bent_maps, the encounter is rejected).
  double wide_moved_xy = 0.0;     // m
  double wide_moved_theta = 0.0;  // rad
  bool settled_by_wide_fit = false;  // the directions disagreed; their wide fits agreed
};

// One robot's half of an encounter, computed on that robot alone: the other
// robot's scan (and surroundings) placed in its own map.
struct PeerPlacement {
  bool valid = false;          // false: the peer's scan had no valid points
  RelativePoseResult located;  // the peer's robot in this robot's map frame
  // `located` refined with the peer's wide surroundings (refine_placement);
  // set only when `located` passes this side's checks and the peer sent them.
  std::optional<Pose2> wide;
};

// `self` is this robot's view (with its map); `peer` what the other robot
// offered (its map is not needed). `seed` drives the random search: both
// robots derive theirs from the pair and the encounter (see protocol).
PeerPlacement locate_peer(const EncounterView& self, const EncounterView& peer, const EncounterConfig& config,
                          std::uint64_t seed);

// The deterministic decision both robots run on the two placements (A is the
// robot whose name sorts first): the same inputs give the same answer on
// either side, so both merge or neither does.
EncounterEstimate decide_encounter(const Pose2& a_pose, const Pose2& b_pose, const PeerPlacement& a_locates_b,
                                   const PeerPlacement& b_locates_a, const EncounterConfig& config);

// Both halves and the decision in one call (A locates with `seed`, B with
// `seed + 1`): for tests and benchmarks that hold both robots' views.
EncounterEstimate estimate_encounter(const EncounterView& a, const EncounterView& b, const EncounterConfig& config,
                                     std::uint64_t seed);

}  // namespace dsswarm
