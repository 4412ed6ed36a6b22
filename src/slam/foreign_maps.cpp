#include "slam/foreign_maps.hpp"

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

// Centre and radius of a piece's evidence on its finest level.
void measure(const FrozenMap& map, const MapConfig& config, ForeignPieceInfo& info) {
  MapConfig finest = config;
  finest.levels = 1;
  const MultiResMap thawed = map.thaw(finest);
  CellIndex lo, hi;
  thawed.finest().bounds(lo, hi);
  const double r = config.resolution;
  const Eigen::Vector2d a(lo.x * r, lo.y * r), b(hi.x * r, hi.y * r);
  info.centre = 0.5 * (a + b);
  info.radius = 0.5 * (b - a).norm();
}

}  // namespace

void follow_piece(int piece, Pose2& then, Pose2& relative, const std::vector<ForeignPieceInfo>& pieces) {
  if (piece < 0 || static_cast<std::size_t>(piece) >= pieces.size()) return;
  const Pose2& now = pieces[static_cast<std::size_t>(piece)].piece.pose;
  if (now == then) return;
  relative = now * then.inverse() * relative;
  then = now;
}

void follow_pieces(std::vector<Constraint>& constraints, const std::vector<ForeignPieceInfo>& pieces) {
  for (Constraint& c : constraints) follow_piece(c.piece, c.piece_pose, c.relative, pieces);
}

int ForeignMaps::index_of(int frame) {
  const auto it = std::find(frame_ids_.begin(), frame_ids_.end(), frame);
  if (it != frame_ids_.end()) return static_cast<int>(it - frame_ids_.begin());
  frame_ids_.push_back(frame);
  poses_.emplace_back();
  tied_.push_back(false);
  return static_cast<int>(frame_ids_.size()) - 1;
}

int ForeignMaps::graph_index(int frame) const {
  const auto it = std::find(frame_ids_.begin(), frame_ids_.end(), frame);
  return it == frame_ids_.end() ? -1 : static_cast<int>(it - frame_ids_.begin());
}

std::vector<std::size_t> ForeignMaps::set(int frame, const Pose2& frame_pose, const std::vector<ForeignPiece>& pieces) {
  const int g = index_of(frame);
  if (!tied_[static_cast<std::size_t>(g)]) poses_[static_cast<std::size_t>(g)] = frame_pose;
  std::vector<std::size_t> added;
  for (ForeignPieceInfo& held : pieces_)
    if (held.frame == g) held.current = false;
  for (const ForeignPiece& p : pieces) {
    if (!p.map) throw ConfigError("ForeignMaps::set: a piece without evidence");
    const auto key = std::make_pair(frame, p.id);
    if (const auto it = piece_index_.find(key); it != piece_index_.end()) {
      pieces_[it->second].piece.pose = p.pose;
      pieces_[it->second].current = true;
      continue;
    }
    ForeignPieceInfo info{g, p};
    measure(*p.map, map_, info);
    piece_index_[key] = pieces_.size();
    added.push_back(pieces_.size());
    pieces_.push_back(std::move(info));
  }
  return added;
}

Constraint ForeignMaps::encounter(int frame, int node, const Pose2& node_pose, const Pose2& frame_pose) {
  const int g = index_of(frame);
  if (!tied_[static_cast<std::size_t>(g)]) poses_[static_cast<std::size_t>(g)] = frame_pose;
  tied_[static_cast<std::size_t>(g)] = true;
  return {Constraint::Kind::foreign, g, node, between(frame_pose, node_pose)};
}

void ForeignMaps::apply(const std::vector<Pose2>& optimized) {
  // Frames added since the round began keep their estimates.
  for (std::size_t i = 0; i < optimized.size() && i < poses_.size(); ++i) poses_[i] = optimized[i];
}

Pose2 ForeignMaps::frame_pose(int frame) const {
  const int g = graph_index(frame);
  if (g < 0) throw ConfigError("ForeignMaps::frame_pose: unknown frame");
  return poses_[static_cast<std::size_t>(g)];
}

std::size_t ForeignMaps::memory_bytes() const {
  // The pieces' maps are shared with the swarm layer's copy of that robot's map.
  return pieces_.capacity() * sizeof(ForeignPieceInfo) + poses_.capacity() * sizeof(Pose2);
}

}  // namespace dsswarm
