#include "swarm/swarm_agent.hpp"

#include "swarm/map_merge.hpp"

#include <algorithm>

#include "common/hash.hpp"
#include "common/rng.hpp"

namespace dsswarm {

namespace {

// A saved snapshot's layer of `self` (its own map); an empty layer if it has none.
const MapLayer& own_layer_of(const MapSnapshot& saved, const std::string& self) {
  static const MapLayer none;
  for (const MapLayer& l : saved.layers)
    if (l.origin == self) return l;
  return none;
}

}  // namespace

SlamConfig agent_slam_config(const SlamConfig& swarm, const std::string& name) {
  SlamConfig c = swarm;
  c.seed = stream_seed(swarm.seed, fnv1a64(name));
  return c;
}

SwarmAgent::SwarmAgent(std::string name, const SlamConfig& config, Executor* background)
    : name_(std::move(name)), slam_(config, background), knowledge_(name_) {}

SwarmAgent::SwarmAgent(std::string name, const SlamConfig& config, const MapSnapshot& saved, const Pose2& pose,
                       Executor* background, const std::optional<Pose2>& odometry)
    : name_(std::move(name)),
      slam_(config, own_layer_of(saved, name_).map ? layer_evidence(own_layer_of(saved, name_)) : MultiResMap(config.map), pose,
            MapUse::extend, background, odometry),
      knowledge_(name_),
      version_base_(own_layer_of(saved, name_).version) {
  for (const MapPiece& p : own_layer_of(saved, name_).pieces) saved_pieces_[p.id] = p.pose;
  // The first id after the saved ones: its peers hold those, and the saved
  // map comes back as one new submap.
  if (!saved_pieces_.empty()) piece_id_base_ = std::max(0, saved_pieces_.rbegin()->first + 1);
  knowledge_.restore(saved);
  register_layers();
  untied_since_resume_ = loop_closing() && knowledge_.size() > 0;
  if (knowledge_.size() > 0) slam_.replace_working_map(compose_working_map(slam_.own_map(), knowledge_.layers()));
  working_layers_ = layer_versions(knowledge_.layers());
}

SlamStep SwarmAgent::process(const LaserScan& scan) {
  last_scan_ = scan;
  const std::size_t before = own_version();
  SlamStep step = slam_.process(scan);
  if (untied_since_resume_) tie_saved_frames(step.pose);
  if (own_version() != before && schedule_.keeps_scans())
    schedule_.inserted(own_version(), scan.timestamp, step.pose, scan.laser_offset,
                       scan_to_points(scan, slam_.config().points));
  sync_frames();
  return step;
}

void SwarmAgent::finish(bool compose) {
  slam_.finish();
  if (!loop_closing() || knowledge_.size() == 0) return;
  sync_frames();
  if (!compose) return;
  slam_.replace_working_map(compose_working_map(slam_.own_map(), knowledge_.layers()));
  working_layers_ = layer_versions(knowledge_.layers());
}

int SwarmAgent::frame_id(const std::string& origin) {
  return frame_ids_.try_emplace(origin, static_cast<int>(frame_ids_.size())).first->second;
}

void SwarmAgent::register_layers() {
  if (!loop_closing()) return;
  for (const MapLayer& l : knowledge_.layers()) slam_.set_foreign_map(frame_id(l.origin), l.origin_in_holder, l.pieces);
}

void SwarmAgent::sync_frames() {
  for (const auto& [origin, id] : frame_ids_)
    if (const std::optional<Pose2> p = slam_.foreign_frame(id)) knowledge_.place(origin, *p);
}

void SwarmAgent::tie(const std::string& peer, std::size_t scan_index, const Pose2& scan_pose, const Pose2& peer_in_self,
                     std::uint64_t encounter) {
  if (!loop_closing()) return;
  slam_.add_encounter(frame_id(peer), scan_index, scan_pose, peer_in_self, encounter);
}

MapMoves SwarmAgent::moves(const std::string& peer, const std::vector<TieScan>& ties,
                           std::size_t max_closures) const {
  MapMoves m;
  if (!loop_closing()) return m;
  if (const auto it = frame_ids_.find(peer); it != frame_ids_.end())
    m.closures = slam_.loop_closer().closures_into(it->second, max_closures);
  m.revision = graph_revision();
  for (const MapPiece& p : own_pieces()) m.pieces.push_back({p.id, p.pose});
  for (const TieScan& t : ties)
    if (t.scan_index < slam_.scans_processed())
      m.ties.push_back({t.encounter, t.offered, slam_.scan_pose(t.scan_index)});
  return m;
}

std::vector<std::pair<const char*, std::size_t>> SwarmAgent::loop_counters() const {
  const LoopCloser& closer = slam_.loop_closer();
  return {{"loop_closures", closer.stats().accepted},
          {"loop_closures_into_others_maps", closer.stats().foreign_accepted},
          {"closures_from_others", closer.peer_closures()}};
}

bool SwarmAgent::follow(const std::string& origin, const MapMoves& moves) {
  if (!loop_closing()) return false;
  bool moved = knowledge_.move_pieces(origin, moves.pieces);
  if (moved) register_layers();
  if (const auto it = frame_ids_.find(origin); it != frame_ids_.end()) {
    for (const TieMove& t : moves.ties) moved = slam_.move_encounter(it->second, t.encounter, t.then, t.now) || moved;
    slam_.set_peer_closures(it->second, closures_into_this_run(moves.closures));
  }
  return moved;
}

// The frames the checkpoint knew, where it knew them, tied to our first
// node: the graph then places them again (their closures weigh at once),
// as the encounters that placed them before the crash did.
void SwarmAgent::tie_saved_frames(const Pose2& pose) {
  const ForeignMaps& foreign = slam_.loop_closer().foreign();
  const auto tied = [&](int frame) {
    const int g = foreign.graph_index(frame);
    return g >= 0 && foreign.tied()[static_cast<std::size_t>(g)];
  };
  untied_since_resume_ = false;
  for (const MapLayer& l : knowledge_.layers()) {
    const int frame = frame_id(l.origin);
    if (tied(frame)) continue;
    slam_.add_encounter(frame, slam_.scans_processed() - 1, pose, l.origin_in_holder);
    untied_since_resume_ = untied_since_resume_ || !tied(frame);  // no node yet: at the next scan
  }
}

std::vector<MapPiece> SwarmAgent::own_pieces() const {
  std::vector<MapPiece> pieces = slam_.finished_pieces();
  for (MapPiece& p : pieces) p.id += piece_id_base_;
  return pieces;
}

std::vector<PeerClosure> SwarmAgent::closures_into_this_run(const std::vector<PeerClosure>& told) const {
  std::vector<PeerClosure> ours;
  for (PeerClosure c : told) {
    if (c.submap < piece_id_base_) {
      // A submap of an earlier run: the saved map, now submap 0, holds it at its saved pose.
      const auto saved = saved_pieces_.find(c.submap);
      if (saved == saved_pieces_.end()) continue;
      c.in_cells = saved->second * c.in_cells;
      c.submap = 0;
    } else {
      c.submap -= piece_id_base_;
    }
    ours.push_back(c);
  }
  return ours;
}

EncounterView SwarmAgent::view(const RelativePoseConfig& config) const {
  EncounterView v;
  v.map = &placement_map();
  v.pose = slam_.pose();
  v.scan_index = slam_.scans_processed() > 0 ? slam_.scans_processed() - 1 : 0;
  if (last_scan_) v.points = scan_to_points(*last_scan_, slam_.config().points);
  if (config.place_in_recent_submaps && slam_.config().loop_closure.enabled)
    v.recent_map = std::make_shared<const MultiResMap>(slam_.unfinished_map());
  v.surroundings = surroundings_points(slam_.own_map(), v.pose, config.surroundings_radius,
                                        config.surroundings_points);
  // With loop closure the wide fit only settles directions that disagree
  // (EncounterConfig::wide_fit_settles_only).
  if (config.merge_surroundings_radius > 0.0)
    v.wide_surroundings = surroundings_points(slam_.own_map(), v.pose, config.merge_surroundings_radius,
                                              config.merge_surroundings_points);
  return v;
}

const MultiResMap& SwarmAgent::own_copy() const {
  if (!own_copy_ || own_copy_version_ != own_version()) {
    own_copy_ = std::make_shared<const MultiResMap>(slam_.own_map());
    own_copy_version_ = own_version();
  }
  return *own_copy_;
}

MapSnapshot SwarmAgent::snapshot() const { return knowledge_.snapshot(own_layer()); }

MapLayer SwarmAgent::own_layer() const {
  if (!loop_closing()) {
    own_copy();
    return MapLayer{name_, own_copy_version_, Pose2{}, 0, own_copy_, {}};
  }
  return MapLayer{name_, own_version(), Pose2{}, 0, std::make_shared<const MultiResMap>(slam_.unfinished_map()),
                  own_pieces()};
}

std::optional<LiveMapParts> SwarmAgent::live_map_parts() const {
  if (!loop_closing() || slam_.localizing_only()) return std::nullopt;
  return dsswarm::live_map_parts(slam_, knowledge_.layers());
}

std::vector<LayerVersion> SwarmAgent::inventory() const {
  std::vector<LayerVersion> out{{name_, own_version(), 0}};
  for (const MapLayer& l : knowledge_.layers()) out.push_back({l.origin, l.version, l.hops});
  return out;
}

bool SwarmAgent::merge(const MapSnapshot& snapshot, const Pose2& sender_in_self) {
  if (!absorb(snapshot, sender_in_self)) return false;
  slam_.replace_working_map(compose_working_map(slam_.own_map(), knowledge_.layers()));
  working_layers_ = layer_versions(knowledge_.layers());
  return true;
}

bool SwarmAgent::absorb(const MapSnapshot& snapshot, const Pose2& sender_in_self) {
  if (!knowledge_.absorb(snapshot, sender_in_self)) return false;
  register_layers();
  sync_frames();  // frames our graph already places keep their place
  return true;
}

void SwarmAgent::schedule_merge(std::uint64_t encounter, double view_stamp,
                                std::shared_ptr<const MultiResMap> own_at_view, std::size_t version_at_view) {
  if (!own_at_view || !schedule_.replays_from(version_at_view, own_version())) {
    own_copy();  // the scans since the view are gone: from the own map now
    own_at_view = own_copy_;
    version_at_view = own_copy_version_;
  }
  schedule_.add({std::move(own_at_view), version_at_view, knowledge_.layers()}, view_stamp, encounter);
}

std::optional<SwarmAgent::Installed> SwarmAgent::install_due(double stamp, bool compose_here) {
  std::optional<MergeSchedule::Due> due = schedule_.take_due(stamp, compose_here);
  if (!due) return std::nullopt;
  slam_.replace_working_map(std::move(due->working));
  working_layers_ = std::move(due->layers);
  return Installed{std::move(due->encounters), due->late};
}

std::shared_ptr<const MultiResMap> SwarmAgent::fresher_placement_map() const {
  if (loop_closing()) return nullptr;  // the own map is placed in: nothing to bring up to date
  return composed_if_behind(slam_.own_map(), working_layers_, knowledge_.layers());
}

std::shared_ptr<const MultiResMap> SwarmAgent::composed_if_behind(const MultiResMap& own,
                                                                 const std::vector<LayerVersion>& held,
                                                                 const std::vector<MapLayer>& layers) {
  if (held == layer_versions(layers)) return nullptr;
  return std::make_shared<const MultiResMap>(compose_working_map(own, layers));
}

}  // namespace dsswarm
