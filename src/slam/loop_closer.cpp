#include "slam/loop_closer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "common/errors.hpp"
#include "slam/loop_round.hpp"

namespace dsswarm {

void LoopClosureConfig::validate() const {
  if (!(node_spacing > 0.0) || !(node_rotation > 0.0))
    throw ConfigError("loop_closure.node_spacing and node_rotation must be > 0");
  if (overlap_nodes < 1) throw ConfigError("loop_closure.overlap_nodes must be >= 1");
  if (!(search_spacing >= 0.0)) throw ConfigError("loop_closure.search_spacing must be >= 0");
  if (!(max_distance > 0.0)) throw ConfigError("loop_closure.max_distance must be > 0");
  if (max_submaps < 1) throw ConfigError("loop_closure.max_submaps must be >= 1");
  if (!(reclose_travel >= 0.0)) throw ConfigError("loop_closure.reclose_travel must be >= 0");
  if (!(window_xy > 0.0) || !(window_xy_per_m >= 0.0) || !(max_window_xy >= window_xy))
    throw ConfigError("loop_closure.window_xy must be > 0, window_xy_per_m >= 0, max_window_xy >= window_xy");
  if (!(window_theta > 0.0) || !(window_theta_per_m >= 0.0) || !(max_window_theta >= window_theta) ||
      !(max_window_theta <= 3.2))
    throw ConfigError(
        "loop_closure.window_theta must be > 0, window_theta_per_m >= 0, max_window_theta in [window_theta, 3.2]");
  if (!(consistency_travel > 0.0) || !(agree_xy > 0.0) || !(agree_theta > 0.0))
    throw ConfigError("loop_closure.consistency_travel, agree_xy and agree_theta must be > 0");
  if (pending_rounds < 0) throw ConfigError("loop_closure.pending_rounds must be >= 0");
  if (!(max_residual_xy > 0.0) || !(max_residual_theta > 0.0))
    throw ConfigError("loop_closure.max_residual_xy and max_residual_theta must be > 0");
  if (round_nodes < 1) throw ConfigError("loop_closure.round_nodes must be >= 1");
  if (rounds_in_flight < 1) throw ConfigError("loop_closure.rounds_in_flight must be >= 1");
  if (foreign_max_pieces < 0 || foreign_backlog < 0)
    throw ConfigError("loop_closure.foreign_max_pieces and foreign_backlog must be >= 0");
  search.validate();
  graph.validate();
}

LoopCloser::LoopCloser(const LoopClosureConfig& config, const MapConfig& map, const PointWeightConfig& weights,
                       std::uint64_t seed, Executor* executor)
    : config_(config),
      map_(map),
      weights_(weights),
      seed_(seed),
      executor_(executor ? executor : &inline_),
      foreign_(map) {}

LoopCloser::~LoopCloser() {
  // A round still running reads data this object shares with it.
  if (!in_flight_.empty()) executor_->wait_for(in_flight_.back().ticket);
}

void LoopCloser::add_fixed_submap() {
  submaps_.push_back({Pose2(), {}, 0.0, 0.0, nullptr, true});
}

void LoopCloser::note_finished(const Submaps& submaps) {
  for (const auto& s : submaps.finished()) {
    const auto id = static_cast<std::size_t>(s->id);
    if (id >= submaps_.size()) submaps_.resize(id + 1);
    SubmapRecord& r = submaps_[id];
    if (r.finished) continue;
    r.finished = s;
    r.anchor = s->anchor;
    r.travel_end = travel_;
  }
}

void LoopCloser::add_scan(std::size_t index, const Pose2& local_pose, std::optional<int> submap,
                          const std::vector<ScanPoint>& points, const Submaps& submaps) {
  if (last_scan_pose_) travel_ += std::hypot(local_pose.x - last_scan_pose_->x, local_pose.y - last_scan_pose_->y);
  last_scan_pose_ = local_pose;
  if (submap) {
    const auto id = static_cast<std::size_t>(*submap);
    if (id >= submaps_.size()) submaps_.resize(id + 1);
    SubmapRecord& r = submaps_[id];
    if (r.nodes.empty() && !r.finished) {
      r.anchor = submaps.current().id == *submap ? submaps.current().anchor : submaps.finished().back()->anchor;
      r.travel_begin = travel_;
    }
    bool node = r.nodes.empty() || nodes_.empty();
    if (!node) {
      const Pose2 d = between(nodes_.back().local, local_pose);
      node = std::hypot(d.x, d.y) >= config_.node_spacing || std::abs(d.theta) >= config_.node_rotation;
    }
    if (node) add_node(index, local_pose, *submap, points);
  }
  if (index != scans_.size()) throw ConfigError("LoopCloser::add_scan: scans out of order");
  const int n = static_cast<int>(nodes_.size()) - 1;
  scans_.push_back({n, n >= 0 ? between(nodes_.back().local, local_pose) : local_pose});
  note_finished(submaps);
  if (config_.enabled && nodes_since_round_ >= config_.round_nodes) start_round();
}

void LoopCloser::add_node(std::size_t index, const Pose2& local_pose, int submap, const std::vector<ScanPoint>& points) {
  const int id = static_cast<int>(nodes_.size());
  Node node{index, local_pose, submap, travel_, nullptr};
  if (config_.enabled && travel_ - last_search_travel_ >= config_.search_spacing) {
    node.points = std::make_shared<const CompactScan>(points);
    last_search_travel_ = travel_;
  }
  SubmapRecord& r = submaps_[static_cast<std::size_t>(submap)];
  constraints_.push_back({Constraint::Kind::local, submap, id, between(r.anchor, local_pose)});
  // The first nodes of a submap in the one before, where local SLAM put them
  // (for the first submap in a given map: where its first scan was located).
  const int own_nodes = static_cast<int>(r.nodes.size());
  if (submap > 0 && own_nodes < config_.overlap_nodes) {
    const SubmapRecord& before = submaps_[static_cast<std::size_t>(submap - 1)];
    if (!before.nodes.empty() || before.fixed)
      constraints_.push_back({Constraint::Kind::local, submap - 1, id, between(before.anchor, local_pose)});
  }
  r.nodes.push_back(id);
  nodes_.push_back(std::move(node));
  ++nodes_since_round_;
}

void LoopCloser::set_foreign_map(int frame, const Pose2& frame_pose, const std::vector<ForeignPiece>& pieces) {
  const std::vector<std::size_t> added = foreign_.set(frame, frame_pose, pieces);
  new_pieces_.insert(new_pieces_.end(), added.begin(), added.end());
}

void LoopCloser::add_encounter(int frame, std::size_t index, const Pose2& scan_pose, const Pose2& frame_pose,
                               std::uint64_t encounter) {
  const ScanRecord& s = scans_.at(index);
  if (s.node < 0) return;  // before the first node: nothing to tie it to
  const Pose2 node_pose = scan_pose * s.relative.inverse();
  constraints_.push_back(foreign_.encounter(frame, s.node, node_pose, frame_pose));
  if (encounter != 0) ties_[{frame, encounter}] = {constraints_.size() - 1, constraints_.back().relative};
  new_constraints_ = true;
}

bool LoopCloser::move_encounter(int frame, std::uint64_t encounter, const Pose2& then, const Pose2& now) {
  const auto it = ties_.find({frame, encounter});
  if (it == ties_.end()) return false;
  // The tie places our node in that robot's frame through its scan: where
  // the scan moves, the node goes with it.
  Pose2& relative = constraints_[it->second.constraint].relative;
  const Pose2 moved = now * then.inverse() * it->second.measured;
  if (moved == relative) return false;
  relative = moved;
  new_constraints_ = true;
  return true;
}

std::optional<Pose2> LoopCloser::frame_pose(int frame) const {
  if (foreign_.graph_index(frame) < 0) return std::nullopt;
  return foreign_.frame_pose(frame);
}

// Our earlier nodes near pieces new to us search them too, a few a round.
void LoopCloser::queue_backlog() {
  for (std::size_t k : new_pieces_) {
    const ForeignPieceInfo& info = foreign_.pieces()[k];
    const Pose2 cells = foreign_.frame_poses()[static_cast<std::size_t>(info.frame)] * info.piece.pose;
    const Eigen::Vector2d centre = cells * info.centre;
    for (std::size_t i = 0; i < searched_up_to_; ++i) {
      if (!nodes_[i].points) continue;
      const Pose2 p = node_global(static_cast<int>(i));
      if (std::hypot(p.x - centre.x(), p.y - centre.y()) - info.radius <= config_.max_distance)
        backlog_.push_back({static_cast<int>(i), nodes_[i].points, k});
    }
  }
  new_pieces_.clear();
}

void LoopCloser::revise_scan(std::size_t index, const Pose2& local_pose) {
  ScanRecord& s = scans_.at(index);
  s.relative = s.node >= 0 ? between(nodes_[static_cast<std::size_t>(s.node)].local, local_pose) : local_pose;
}

TrajectoryNode LoopCloser::node(std::size_t i) const {
  const Node& n = nodes_.at(i);
  const Pose2& anchor = submaps_[static_cast<std::size_t>(n.submap)].anchor;
  return {n.scan, n.submap, n.local, between(anchor, n.local), node_global(static_cast<int>(i)), n.points != nullptr};
}

Pose2 LoopCloser::node_global(int node) const {
  const auto i = static_cast<std::size_t>(node);
  return i < applied_.nodes.size() ? applied_.nodes[i] : applied_.global_from_local * nodes_[i].local;
}

Pose2 LoopCloser::submap_cells_pose(int submap) const {
  const auto i = static_cast<std::size_t>(submap);
  // Not optimized yet: moved with the rest of the trajectory.
  if (i >= applied_.submaps.size()) return applied_.global_from_local;
  return applied_.submaps[i] * submaps_[i].anchor.inverse();
}

std::vector<Pose2> LoopCloser::trajectory() const {
  std::vector<Pose2> out;
  out.reserve(scans_.size());
  for (std::size_t i = 0; i < scans_.size(); ++i) out.push_back(scan_pose(i));
  return out;
}

Pose2 LoopCloser::scan_pose(std::size_t index) const {
  const ScanRecord& s = scans_.at(index);
  return s.node >= 0 ? node_global(s.node) * s.relative : s.relative;
}

std::vector<Pose2> LoopCloser::local_trajectory() const {
  std::vector<Pose2> out;
  out.reserve(scans_.size());
  for (const ScanRecord& s : scans_)
    out.push_back(s.node >= 0 ? nodes_[static_cast<std::size_t>(s.node)].local * s.relative : s.relative);
  return out;
}

std::size_t LoopCloser::memory_bytes() const {
  std::size_t n = nodes_.capacity() * sizeof(Node) + scans_.capacity() * sizeof(ScanRecord) +
                  (constraints_.capacity() + applied_.closures.capacity()) * sizeof(Constraint) +
                  applied_.nodes.capacity() * sizeof(Pose2);
  for (const Node& node : nodes_)
    if (node.points) n += node.points->memory_bytes();
  for (const SubmapRecord& r : submaps_) n += r.nodes.capacity() * sizeof(int);
  return n + foreign_.memory_bytes();
}

void LoopCloser::start_round() {
  while (static_cast<int>(in_flight_.size()) >= config_.rounds_in_flight) apply_oldest();
  nodes_since_round_ = 0;
  queue_backlog();  // nodes searched before: the new ones search every piece anyway
  auto round = std::make_shared<Round>();
  round->scratch = scratch_;
  RoundInput& in = round->in;
  in.map = map_;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    in.node_local.push_back(nodes_[i].local);
    in.node_submap.push_back(nodes_[i].submap);
    in.node_travel.push_back(nodes_[i].travel);
    if (nodes_[i].points && i >= searched_up_to_) in.searches.push_back({static_cast<int>(i), nodes_[i].points});
  }
  searched_up_to_ = nodes_.size();
  for (const SubmapRecord& r : submaps_)
    in.submaps.push_back({r.finished, r.nodes, r.anchor, r.finished ? r.travel_end : travel_, r.fixed});
  in.graph.constraints = constraints_;
  in.graph.frames = foreign_.frame_poses();
  in.frame_tied = foreign_.tied();
  add_peer_constraints(in);
  in.graph.fixed_submap = 0;
  in.foreign = foreign_.pieces();
  const std::size_t take = std::min(backlog_.size(), static_cast<std::size_t>(config_.foreign_backlog));
  in.backlog.assign(backlog_.begin(), backlog_.begin() + static_cast<std::ptrdiff_t>(take));
  backlog_.erase(backlog_.begin(), backlog_.begin() + static_cast<std::ptrdiff_t>(take));
  in.new_constraints = std::exchange(new_constraints_, false);
  // It starts from the round before it, or from what local SLAM holds now.
  if (!in_flight_.empty())
    round->previous = in_flight_.back().round;
  else
    round->base = applied_;
  Round* job = round.get();
  const LoopClosureConfig config = config_;
  const PointWeightConfig weights = weights_;
  const std::uint64_t seed = seed_;
  const std::uint64_t ticket = executor_->submit([job, config, weights, seed] { run_round(*job, config, weights, seed); });
  in_flight_.push_back({std::move(round), ticket});
}

void LoopCloser::add_peer_constraints(RoundInput& in) const {
  for (const auto& [frame, closures] : peer_closures_) {
    const int g = foreign_.graph_index(frame);
    if (g < 0 || !in.frame_tied[static_cast<std::size_t>(g)]) continue;  // not placed by an encounter of ours
    for (const PeerClosure& c : closures) {
      // Submap ids are indices; one we never made (a confused peer) is left out.
      if (c.submap < 0 || static_cast<std::size_t>(c.submap) >= submaps_.size()) continue;
      const Pose2 relative = between(submaps_[static_cast<std::size_t>(c.submap)].anchor, c.in_cells);
      in.graph.peer.push_back({c.submap, g, c.node, relative});
    }
  }
}

std::vector<PeerClosure> LoopCloser::closures_into(int frame, std::size_t max) const {
  std::vector<PeerClosure> out;
  const int g = foreign_.graph_index(frame);
  if (g < 0) return out;
  const std::vector<ForeignPieceInfo>& pieces = foreign_.pieces();
  for (auto it = applied_.closures.rbegin(); it != applied_.closures.rend() && out.size() < max; ++it) {
    const Constraint& c = *it;
    if (c.kind != Constraint::Kind::foreign || c.submap != g || c.piece < 0) continue;
    const ForeignPieceInfo& piece = pieces[static_cast<std::size_t>(c.piece)];
    out.push_back({piece.piece.id, c.piece_pose.inverse() * c.relative, node_global(c.node)});
  }
  std::reverse(out.begin(), out.end());
  return out;
}

void LoopCloser::set_peer_closures(int frame, std::vector<PeerClosure> closures) {
  std::vector<PeerClosure>& held = peer_closures_[frame];
  if (held == closures) return;
  held = std::move(closures);
  new_constraints_ = true;  // the next round optimizes with them
}

std::size_t LoopCloser::peer_closures() const {
  std::size_t n = 0;
  for (const auto& [frame, closures] : peer_closures_) n += closures.size();
  return n;
}

LoopClosure LoopCloser::record(const LoopCandidate& c) const {
  const std::size_t scan = nodes_[static_cast<std::size_t>(c.node)].scan;
  if (c.foreign)
    return {scan, foreign_.frames()[static_cast<std::size_t>(c.submap)], true, std::nullopt, c.relative, std::nullopt,
            Pose2(), c.score, c.inliers, c.same_side};
  const SubmapRecord& r = submaps_[static_cast<std::size_t>(c.submap)];
  LoopClosure closure{scan, c.submap, false, std::nullopt, c.relative, std::nullopt, Pose2(), c.score, c.inliers,
                      c.same_side};
  double nearest = std::numeric_limits<double>::infinity();
  for (int n : r.nodes) {
    const Node& node = nodes_[static_cast<std::size_t>(n)];
    if (!closure.anchor_scan) closure.anchor_scan = node.scan;
    const Pose2 in_submap = between(r.anchor, node.local);
    const double d = std::hypot(in_submap.x - c.relative.x, in_submap.y - c.relative.y);
    if (d < nearest) {
      nearest = d;
      closure.nearest_scan = node.scan;
      closure.relative_to_nearest = between(in_submap, c.relative);
    }
  }
  return closure;
}

void LoopCloser::apply_oldest() {
  const InFlight oldest = std::move(in_flight_.front());
  in_flight_.pop_front();
  executor_->wait_for(oldest.ticket);
  const RoundOutput& out = oldest.round->out;
  add_stats(stats_, out.stats);
  ++stats_.rounds;
  for (const LoopCandidate& c : out.accepted) closures_.push_back(record(c));
  applied_ = out.state;
  if (!out.optimized) return;
  ++stats_.optimizations;
  foreign_.apply(applied_.frames);
  ++version_;
}

void LoopCloser::finish(const Submaps& submaps) {
  note_finished(submaps);
  if (!config_.enabled) return;
  start_round();  // hands over what is left
  while (!in_flight_.empty()) apply_oldest();
}

}  // namespace dsswarm
