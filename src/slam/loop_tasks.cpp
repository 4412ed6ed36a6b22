#include "slam/loop_tasks.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace dsswarm::round_detail {
namespace {

Pose2 prior_in(const RoundInput& in, int node, int submap) {
  return in.submaps[static_cast<std::size_t>(submap)].anchor *
         between(in.graph.submaps[static_cast<std::size_t>(submap)], in.graph.nodes[static_cast<std::size_t>(node)]);
}

// Where a foreign piece's cells lie in our global frame now.
Pose2 piece_global(const RoundInput& in, const ForeignPieceInfo& p) {
  return in.graph.frames[static_cast<std::size_t>(p.frame)] * p.piece.pose;
}

// The finished submaps worth searching for `node`: not its own nor the one
// before (local SLAM matched it against those), with a node within
// max_distance of it (any given map counts as near), nearest first.
std::vector<int> nearby_submaps(const RoundInput& in, int node, const LoopClosureConfig& config) {
  const Pose2& p = in.graph.nodes[static_cast<std::size_t>(node)];
  const int own = in.node_submap[static_cast<std::size_t>(node)];
  std::vector<std::pair<double, int>> near;
  for (int s = 0; s < static_cast<int>(in.submaps.size()); ++s) {
    const RoundInput::SubmapInfo& info = in.submaps[static_cast<std::size_t>(s)];
    if (!info.finished || s >= own - 1) continue;
    double nearest = info.fixed ? 0.0 : config.max_distance + 1.0;
    for (int n : info.nodes) {
      const Pose2& q = in.graph.nodes[static_cast<std::size_t>(n)];
      nearest = std::min(nearest, std::hypot(q.x - p.x, q.y - p.y));
    }
    if (nearest <= config.max_distance) near.push_back({nearest, s});
  }
  std::sort(near.begin(), near.end());
  std::vector<int> out;
  for (const auto& [d, s] : near) {
    if (static_cast<int>(out.size()) >= config.max_submaps) break;
    out.push_back(s);
  }
  return out;
}

// How far `node` is from the evidence of foreign piece `k` (0 inside its extent).
double distance_to_piece(const RoundInput& in, int node, std::size_t k) {
  const ForeignPieceInfo& info = in.foreign[k];
  const Pose2& p = in.graph.nodes[static_cast<std::size_t>(node)];
  const Eigen::Vector2d c = piece_global(in, info) * info.centre;
  return std::max(0.0, std::hypot(c.x() - p.x, c.y() - p.y) - info.radius);
}

// Other robots' pieces worth searching for `node`: within max_distance, nearest first.
std::vector<std::size_t> nearby_pieces(const RoundInput& in, int node, const LoopClosureConfig& config) {
  std::vector<std::pair<double, std::size_t>> near;
  for (std::size_t k = 0; k < in.foreign.size(); ++k) {
    if (!in.foreign[k].current) continue;  // no longer sent by its robot: not searched
    if (const double d = distance_to_piece(in, node, k); d <= config.max_distance) near.push_back({d, k});
  }
  std::sort(near.begin(), near.end());
  std::vector<std::size_t> out;
  for (const auto& [d, k] : near) {
    if (static_cast<int>(out.size()) >= config.foreign_max_pieces) break;
    out.push_back(k);
  }
  return out;
}

SearchWindow grown(double d, const LoopClosureConfig& config) {
  return {std::min(config.max_window_xy, config.window_xy + config.window_xy_per_m * d),
          std::min(config.max_window_theta, config.window_theta + config.window_theta_per_m * d)};
}

// Wider the further the robot went since the submap or the last closure.
SearchWindow window_for(const RoundInput& in, int node, int submap, const LoopClosureConfig& config) {
  const double since = std::max(in.submaps[static_cast<std::size_t>(submap)].travel_end, in.last_closure_travel);
  return grown(std::max(0.0, in.node_travel[static_cast<std::size_t>(node)] - since), config);
}

// Wider the further the node is from our nearest node tied to that robot's frame.
SearchWindow foreign_window(const RoundInput& in, int node, const ForeignPieceInfo& piece,
                            const LoopClosureConfig& config) {
  const Pose2& p = in.graph.nodes[static_cast<std::size_t>(node)];
  double nearest = config.max_distance * 10.0;  // never tied: as wide as the window grows
  for (const Constraint& c : in.graph.constraints)
    if (c.kind == Constraint::Kind::foreign && c.submap == piece.frame) {
      const Pose2& q = in.graph.nodes[static_cast<std::size_t>(c.node)];
      nearest = std::min(nearest, std::hypot(q.x - p.x, q.y - p.y));
    }
  return grown(nearest, config);
}

}  // namespace

std::vector<Task> tasks_for(const RoundInput& in, const LoopClosureConfig& config) {
  std::vector<Task> tasks;
  for (const RoundInput::Search& s : in.searches) {
    for (int submap : nearby_submaps(in, s.node, config))
      tasks.push_back({s.node, {false, submap}, window_for(in, s.node, submap, config), s.points.get(),
                       prior_in(in, s.node, submap)});
    for (std::size_t k : nearby_pieces(in, s.node, config)) {
      const ForeignPieceInfo& piece = in.foreign[k];
      tasks.push_back({s.node, {true, static_cast<int>(k)}, foreign_window(in, s.node, piece, config), s.points.get(),
                       between(piece_global(in, piece), in.graph.nodes[static_cast<std::size_t>(s.node)])});
    }
  }
  for (const RoundInput::Backlog& b : in.backlog) {
    const ForeignPieceInfo& piece = in.foreign[b.piece];
    if (!piece.current) continue;
    tasks.push_back({b.node, {true, static_cast<int>(b.piece)}, foreign_window(in, b.node, piece, config),
                     b.points.get(), between(piece_global(in, piece), in.graph.nodes[static_cast<std::size_t>(b.node)])});
  }
  // Target by target, so each one's bounds are built once and freed after.
  std::stable_sort(tasks.begin(), tasks.end(), [](const Task& a, const Task& b) { return a.target < b.target; });
  return tasks;
}

}  // namespace dsswarm::round_detail
