#pragma once
// One robot of the swarm: single-robot SLAM in its own frame, plus what it
// has learnt from the others (per origin, see map_knowledge.hpp). It knows
// nothing of the others until told one is near; then it offers its map and
// current scan, and merges what the other offers once the encounter is
// verified (encounter.hpp). Alone, or if every encounter fails, it is just a
// single robot doing SLAM.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "slam/slam.hpp"
#include "swarm/encounter.hpp"
#include "swarm/live_map.hpp"
#include "swarm/map_knowledge.hpp"
#include "swarm/merge_schedule.hpp"

namespace dsswarm {

// A robot's SLAM settings: the swarm's, with its own random stream derived
// from its name (so a robot process and the in-process swarm agree).
SlamConfig agent_slam_config(const SlamConfig& swarm, const std::string& name);

class SwarmAgent {
 public:
  // `background` runs loop closing (not owned, must outlive the agent;
  // nullptr: on the scan thread). The results are the same either way.
  SwarmAgent(std::string name, const SlamConfig& config, Executor* background = nullptr);
  // Continues from a saved snapshot (a checkpoint): its own layer is the map
  // it goes on mapping in, from `pose` (a wide search places the first scan);
  // the others are what it knew. Its own map's version goes on from the saved
  // one. `odometry`: the reading at `pose` (see Slam's `start_odometry`).
  SwarmAgent(std::string name, const SlamConfig& config, const MapSnapshot& saved, const Pose2& pose,
             Executor* background = nullptr, const std::optional<Pose2>& odometry = std::nullopt);

  SlamStep process(const LaserScan& scan);
  // Waits for loop closing and runs its last round: the trajectory and the
  // own map then reflect every scan (Slam::finish). Processing may go on after.
  // With loop closure on, the merged map is then composed again at the
  // other robots' frames as the last round placed them.
  // `compose` false: the merged map is left for a later finish() (one that
  // follows the others' last word on their maps).
  void finish(bool compose = true);

  // What this robot puts on the table at an encounter: the map it places the
  // peer's scan in (placement_map), current scan, pose and surroundings (as
  // `config` asks).
  EncounterView view(const RelativePoseConfig& config) const;
  // The map a peer's scan is placed in. Without loop closure the working map
  // (own ⊕ foreign), which the robot localizes in too. With loop closure on
  // the robot localizes in its own submaps only, and its pose fits them, not
  // the foreign layers: a layer merged slightly off would pull the placement
  // its way. So the own map.
  const MultiResMap& placement_map() const { return loop_closing() ? slam_.own_map() : slam_.map(); }
  MapSnapshot snapshot() const;      // own map (layer 0) + everything known of others
  // Layer 0 of snapshot(). With loop closure on, the finished submaps go as
  // pieces at their optimized poses, so that holders follow its closures.
  MapLayer own_layer() const;

  // An accepted encounter with `peer`, whose map frame lies at
  // `peer_in_self` in ours, found at our scan `scan_index` (pose `scan_pose`):
  // with loop closure on, a constraint between that scan and the peer's
  // frame in this robot's pose graph (slam/foreign_maps.hpp). From then on
  // the graph places that frame, and knowledge() and the merged map follow.
  // `encounter` names it, for follow().
  void tie(const std::string& peer, std::size_t scan_index, const Pose2& scan_pose, const Pose2& peer_in_self,
           std::uint64_t encounter = 0);

  // Where this robot's map lies now, for `peer` holding a copy (MapMoves):
  // its finished submaps, its scans at the encounters `ties`, and its latest
  // `max_closures` loop closures into the peer's map. Empty with loop closure off.
  MapMoves moves(const std::string& peer, const std::vector<TieScan>& ties, std::size_t max_closures) const;
  // Grows whenever loop closing moves this robot's map (moves() changes).
  std::uint64_t graph_revision() const { return slam_.graph_revision(); }
  // `origin` says its map moved: its pieces held here follow, and so do the
  // ties of our encounters with it, from the next loop-closing round on; its
  // closures into our map join our graph.
  // The merged map shows it from the next composition on (a merge, finish()),
  // as it shows this robot's own closures. Returns whether anything moved.
  bool follow(const std::string& origin, const MapMoves& moves);
  bool loop_closing() const { return slam_.config().loop_closure.enabled; }

  // Takes in another robot's snapshot, whose sender's frame has pose
  // `sender_in_self` here, and rebuilds the working map if anything is new.
  // Returns whether anything was new.
  bool merge(const MapSnapshot& snapshot, const Pose2& sender_in_self);

  // Merging on either path (merge_schedule.hpp): absorb() takes the layers
  // in at once; schedule_merge() queues the merged map, composed from the own
  // map as it stood at the encounter's scan (`own_at_view`, version
  // `version_at_view`; nullptr: the own map now), to take effect `merge_delay`
  // s after that scan; install_due() installs, before a scan, the newest
  // merge due by its stamp. A robot process composes off the scan path
  // (claim_merge_job, MergeSchedule::compose, merge_job_composed); one process composes in
  // install_due (`compose_here`).
  bool absorb(const MapSnapshot& snapshot, const Pose2& sender_in_self);
  void set_merge_delay(double seconds) { schedule_ = MergeSchedule(seconds); }
  void schedule_merge(std::uint64_t encounter, double view_stamp,
                      std::shared_ptr<const MultiResMap> own_at_view = nullptr, std::size_t version_at_view = 0);
  struct Installed {
    std::vector<std::uint64_t> encounters;
    bool late = false;
  };
  std::optional<Installed> install_due(double stamp, bool compose_here);
  bool merges_pending() const { return !schedule_.empty(); }
  bool has_merge_job() const { return schedule_.has_unclaimed(); }
  std::optional<MergeSchedule::Claimed> claim_merge_job() { return schedule_.claim(); }
  void merge_job_composed(std::uint64_t ticket, MultiResMap working) { schedule_.composed(ticket, std::move(working)); }
  // The foreign layers the working map holds; the map to place a peer's scan
  // in when it lacks some the robot holds already (a merge not yet due):
  // composed from the own map now. nullptr: placement_map() holds them all.
  const std::vector<LayerVersion>& working_layers() const { return working_layers_; }
  std::shared_ptr<const MultiResMap> fresher_placement_map() const;
  // own ⊕ `layers` if a map holding `held` lacks some of them, else nullptr:
  // the one rule both paths bring a view's map up to date by.
  static std::shared_ptr<const MultiResMap> composed_if_behind(const MultiResMap& own,
                                                               const std::vector<LayerVersion>& held,
                                                               const std::vector<MapLayer>& layers);

  // What /map shows with loop closure on, taken apart for composing off the
  // scan path (live_map.hpp): own submaps where the graph has them now, and
  // the layers held at their frames now. nullopt without loop closure (or
  // localizing only): then the working map is it, kept as it goes.
  std::optional<LiveMapParts> live_map_parts() const;

  // The layers snapshot() would hold (origin, version, hops), without copying maps.
  std::vector<LayerVersion> inventory() const;
  const std::optional<LaserScan>& last_scan() const { return last_scan_; }

  // Scans in its own map, over every run of this robot (a snapshot's version).
  std::size_t own_version() const { return version_base_ + slam_.scans_inserted(); }
  const std::string& name() const { return name_; }
  const Slam& slam() const { return slam_; }
  // Loop closure's counts for a robot's stats: its closures (into other
  // robots' maps among them) and the other robots' closures into its map.
  std::vector<std::pair<const char*, std::size_t>> loop_counters() const;
  const MapKnowledge& knowledge() const { return knowledge_; }

 private:
  // Other robots' maps in our pose graph (loop closure on): every layer's
  // pieces are searched for closures; the layers' frames follow the graph.
  int frame_id(const std::string& origin);
  void register_layers();
  void sync_frames();
  // Our finished submaps as peers know them (ids from piece_id_base_), and
  // peers' closures into them as our loop closer knows them (those into a
  // saved piece go into submap 0, the saved map, where that piece lies).
  std::vector<MapPiece> own_pieces() const;
  std::vector<PeerClosure> closures_into_this_run(const std::vector<PeerClosure>& told) const;
  void tie_saved_frames(const Pose2& pose);  // resumed: at the first node that takes them

  std::string name_;
  Slam slam_;
  MapKnowledge knowledge_;
  std::map<std::string, int> frame_ids_;  // origin -> frame id in our graph
  std::optional<LaserScan> last_scan_;
  std::size_t version_base_ = 0;  // own map version when this run began (resumed)
  // Submap ids peers know: this run's submap k is piece_id_base_ + k. A
  // resumed robot goes on after the saved pieces, which peers still hold
  // (reused ids would stand for other evidence, and their closures into
  // the saved submaps would land in new ones).
  std::int32_t piece_id_base_ = 0;
  std::map<std::int32_t, Pose2> saved_pieces_;  // resumed: the saved pieces' poses in the saved map
  bool untied_since_resume_ = false;  // resumed: frames known but not yet tied into our graph
  MergeSchedule schedule_;
  std::vector<LayerVersion> working_layers_;
  const MultiResMap& own_copy() const;
  // Frozen copy of the own map for snapshots, refreshed when the map grew.
  mutable std::shared_ptr<const MultiResMap> own_copy_;
  mutable std::size_t own_copy_version_ = 0;
};

}  // namespace dsswarm
