#pragma once
// Global SLAM for one robot: the trajectory nodes and submaps of local SLAM
// in a pose graph, loop closures searched between new nodes and finished
// submaps nearby, and the graph optimized — in rounds that run in the
// background (an Executor) while local SLAM goes on.
//
// Every `round_nodes` nodes a round is handed to the executor: a snapshot of
// the graph, the new nodes to search and the finished submaps (immutable,
// shared). It searches (loop_search.hpp), keeps the verified candidates that
// agree with another closure (pairwise consistency), optimizes with them,
// drops any that the optimized graph does not bear out, and re-optimizes.
// Rounds run one after the other, each starting from what the one before
// concluded (LoopState). A round's result is applied `rounds_in_flight`
// hand-overs later — all at once, between two scans — so the background has
// that long before local SLAM would have to wait, and the outcome depends
// only on the scans, not on how fast the background ran: the same seed gives
// the same map, on one thread or two.
//
// Local SLAM runs in its own local frame and never jumps; global poses are
// local poses moved by the optimized graph.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "geometry/pose2.hpp"
#include "sensor/scan_points.hpp"
#include "slam/compact_scan.hpp"
#include "slam/executor.hpp"
#include "slam/foreign_maps.hpp"
#include "slam/loop_round.hpp"
#include "slam/loop_search.hpp"
#include "slam/pose_graph.hpp"
#include "slam/submaps.hpp"

namespace dsswarm {

// An accepted loop closure, for the record.
struct LoopClosure {
  std::size_t scan = 0;         // the node's scan (process() order)
  int submap = 0;               // foreign: the caller's id of the other robot's frame
  bool foreign = false;         // into another robot's map (relative: in its frame)
  std::optional<std::size_t> anchor_scan;  // the scan the submap's frame is anchored at (none: a given map)
  Pose2 relative;               // the node's pose in the submap's frame
  // The same relative to the submap's node nearest to where the closure put
  // it: free of the drift within the submap, for checking against a truth.
  std::optional<std::size_t> nearest_scan;
  Pose2 relative_to_nearest;
  double score = 0.0, inliers = 0.0, same_side = 0.0;
};

// A trajectory node as the graph holds it.
struct TrajectoryNode {
  std::size_t scan = 0;  // its scan (process() order)
  int submap = 0;        // the submap its scan went into
  Pose2 local;           // local SLAM's pose
  Pose2 in_submap;       // the same in the submap's frame (anchor⁻¹ ⊕ local)
  Pose2 global;          // the best global pose now
  bool searched = false; // kept its points for the loop-closure search
};

class LoopCloser {
 public:
  // `executor` runs the rounds (not owned; nullptr: on the caller's thread).
  LoopCloser(const LoopClosureConfig& config, const MapConfig& map, const PointWeightConfig& weights,
             std::uint64_t seed, Executor* executor = nullptr);
  ~LoopCloser();
  LoopCloser(const LoopCloser&) = delete;
  LoopCloser& operator=(const LoopCloser&) = delete;

  // A given initial map as submap 0, fixed: it defines the global frame.
  void add_fixed_submap();
  // A scan processed by local SLAM at `local_pose`; `submap` is where its
  // evidence went (none: not inserted). Scans must come in process() order.
  void add_scan(std::size_t index, const Pose2& local_pose, std::optional<int> submap,
                const std::vector<ScanPoint>& points, const Submaps& submaps);
  // A better local pose for an earlier scan that is no node (a dropped scan's revision).
  void revise_scan(std::size_t index, const Pose2& local_pose);
  // Waits for the round in flight, runs a last one over what is left
  // (searches and optimization) and applies it.
  void finish(const Submaps& submaps);

  // Another robot's map (foreign_maps.hpp), `frame` being the caller's id for
  // that robot: its finished pieces, searched for loop closures from the next
  // round on, and the frame's pose here as the caller knows it (kept until
  // an encounter ties it into the graph).
  void set_foreign_map(int frame, const Pose2& frame_pose, const std::vector<ForeignPiece>& pieces);
  // An encounter with that robot: at our scan `index` (process() order,
  // global pose `scan_pose` then) its frame was at `frame_pose` (global, then).
  // `encounter` names it for move_encounter (0: it never moves).
  void add_encounter(int frame, std::size_t index, const Pose2& scan_pose, const Pose2& frame_pose,
                     std::uint64_t encounter = 0);
  // That robot's own loop closures moved its scan of encounter `encounter`
  // from `then` (where it stood when the robots met, in its frame) to `now`:
  // the tie follows, from the next round on. Repeating it changes nothing
  // more. Returns whether the tie moved (false for an encounter not tied here).
  bool move_encounter(int frame, std::uint64_t encounter, const Pose2& then, const Pose2& now);
  // Our accepted closures into that robot's submaps, as it needs them to
  // weigh them too (the most recent `max` of them).
  std::vector<PeerClosure> closures_into(int frame, std::size_t max) const;
  // That robot's closures into our submaps (the complete set it holds now):
  // from the next round on, in our graph while its frame is tied to it.
  void set_peer_closures(int frame, std::vector<PeerClosure> closures);
  // Those closures, over every robot, as last told.
  std::size_t peer_closures() const;
  // Where that robot's frame lies in ours now; nullopt if unknown.
  std::optional<Pose2> frame_pose(int frame) const;
  const ForeignMaps& foreign() const { return foreign_; }

  // Global pose of a local pose now (as the latest optimization moved the trajectory).
  Pose2 to_global(const Pose2& local) const { return applied_.global_from_local * local; }
  // Every scan's best global pose, in process() order.
  std::vector<Pose2> trajectory() const;
  Pose2 scan_pose(std::size_t index) const;  // one of them
  // Every scan's local pose (local SLAM's own estimate), in process() order.
  std::vector<Pose2> local_trajectory() const;
  // Where a submap's cells lie globally: global_anchor ⊕ anchor⁻¹.
  Pose2 submap_cells_pose(int submap) const;
  const LoopClosureStats& stats() const { return stats_; }
  const std::vector<LoopClosure>& closures() const { return closures_; }
  // Bumped whenever an optimization moved poses (or other robots' frames).
  std::uint64_t version() const { return version_; }
  // No round handed over and not yet applied (after finish(), say): the
  // executor has nothing of ours to run.
  bool idle() const { return in_flight_.empty(); }
  std::size_t nodes() const { return nodes_.size(); }
  TrajectoryNode node(std::size_t i) const;
  std::size_t memory_bytes() const;

 private:
  struct Node {
    std::size_t scan;
    Pose2 local;
    int submap;
    double travel;                              // m along the trajectory (local SLAM's)
    std::shared_ptr<const CompactScan> points;  // search nodes only
  };
  struct SubmapRecord {
    Pose2 anchor;                               // local
    std::vector<int> nodes;                     // its own (not those tied in from the next one)
    double travel_begin = 0.0, travel_end = 0.0;
    std::shared_ptr<const Submap> finished;     // set once finished
    bool fixed = false;
  };
  struct ScanRecord {
    int node;        // the node it hangs on (-1: before the first node)
    Pose2 relative;  // its pose in that node's frame (local poses)
  };

  void add_node(std::size_t index, const Pose2& local_pose, int submap, const std::vector<ScanPoint>& points);
  void note_finished(const Submaps& submaps);
  void start_round();
  void queue_backlog();
  void apply_oldest();
  void add_peer_constraints(RoundInput& in) const;
  LoopClosure record(const LoopCandidate& c) const;
  Pose2 node_global(int node) const;

  LoopClosureConfig config_;
  MapConfig map_;
  PointWeightConfig weights_;
  std::uint64_t seed_;
  Executor* executor_;
  InlineExecutor inline_;
  std::vector<Node> nodes_;
  std::vector<SubmapRecord> submaps_;
  std::vector<ScanRecord> scans_;
  std::vector<Constraint> constraints_;      // local ones and encounters (closures: applied_)
  LoopState applied_;                        // the latest round's conclusions local SLAM took over
  ForeignMaps foreign_;
  std::vector<std::size_t> new_pieces_;      // foreign pieces not yet searched from earlier nodes
  std::vector<RoundInput::Backlog> backlog_; // those searches, waiting for a round
  bool new_constraints_ = false;             // encounters since the last round
  struct Tie {
    std::size_t constraint;  // in constraints_
    Pose2 measured;          // its relative as the encounter measured it
  };
  std::map<std::pair<int, std::uint64_t>, Tie> ties_;  // (frame, encounter)
  std::map<int, std::vector<PeerClosure>> peer_closures_;  // frame -> its closures into our submaps
  double travel_ = 0.0;
  std::optional<Pose2> last_scan_pose_;
  double last_search_travel_ = -1e9;
  std::size_t searched_up_to_ = 0;           // nodes handed to a round for searching
  int nodes_since_round_ = 0;
  struct InFlight {
    std::shared_ptr<Round> round;
    std::uint64_t ticket;
  };
  std::deque<InFlight> in_flight_;           // handed over, oldest first
  std::shared_ptr<RoundScratch> scratch_ = std::make_shared<RoundScratch>();
  LoopClosureStats stats_;
  std::vector<LoopClosure> closures_;
  std::uint64_t version_ = 0;
};

}  // namespace dsswarm
