#include "eval/relation_graph.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <iterator>
#include <limits>

#include "eval/trajectory_lookup.hpp"

namespace dsswarm {

RelationGraph::RelationGraph(const std::vector<Relation>& relations, double max_time_diff)
    : relations_(relations), max_time_diff_(max_time_diff) {
  require_valid_max_time_diff(max_time_diff);
  std::vector<double> times;
  for (const Relation& r : relations_) {
    if (!std::isfinite(r.t1) || !std::isfinite(r.t2)) continue;
    times.push_back(r.t1);
    times.push_back(r.t2);
  }
  std::sort(times.begin(), times.end());
  // Endpoints within max_time_diff of the node's first time are the same scan.
  for (const double t : times)
    if (node_times_.empty() || t - node_times_.back() > max_time_diff_) node_times_.push_back(t);
  edges_.resize(node_times_.size());
  for (std::size_t i = 0; i < relations_.size(); ++i) {
    const auto n1 = node_at(relations_[i].t1);
    const auto n2 = node_at(relations_[i].t2);
    if (!n1 || !n2 || *n1 == *n2) continue;
    edges_[*n1].push_back({*n2, i, true});
    edges_[*n2].push_back({*n1, i, false});
  }
}

std::optional<std::size_t> RelationGraph::node_at(double t) const {
  if (node_times_.empty() || !std::isfinite(t)) return std::nullopt;
  // Nodes are the first time of their cluster, so a time belongs to the node at or just before it.
  const auto after = std::upper_bound(node_times_.begin(), node_times_.end(), t);
  std::optional<std::size_t> best;
  double best_diff = std::numeric_limits<double>::infinity();
  for (auto it : {after, after == node_times_.begin() ? after : std::prev(after)}) {
    if (it == node_times_.end()) continue;
    const double diff = std::abs(*it - t);
    if (diff <= max_time_diff_ && diff < best_diff) {
      best = static_cast<std::size_t>(it - node_times_.begin());
      best_diff = diff;
    }
  }
  return best;
}

std::optional<RelationGraph::Truth> RelationGraph::motion(double ta, double tb, std::size_t max_hops) const {
  if (!std::isfinite(ta) || !std::isfinite(tb)) return std::nullopt;
  if (std::abs(ta - tb) <= max_time_diff_) return Truth{Pose2(), 0};
  const auto from = node_at(ta);
  const auto to = node_at(tb);
  if (!from || !to || max_hops == 0) return std::nullopt;
  if (*from == *to) return Truth{Pose2(), 0};
  // Breadth-first: fewest relations; edges in file order keep the choice reproducible.
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> depth(node_times_.size(), kNone);
  std::vector<const Edge*> via(node_times_.size(), nullptr);
  std::vector<std::size_t> parent(node_times_.size(), kNone);
  std::deque<std::size_t> queue{*from};
  depth[*from] = 0;
  while (!queue.empty() && depth[*to] == kNone) {
    const std::size_t n = queue.front();
    queue.pop_front();
    if (depth[n] >= max_hops) continue;
    for (const Edge& e : edges_[n]) {
      if (depth[e.to] != kNone) continue;
      depth[e.to] = depth[n] + 1;
      via[e.to] = &e;
      parent[e.to] = n;
      queue.push_back(e.to);
    }
  }
  if (depth[*to] == kNone) return std::nullopt;
  std::vector<const Edge*> path;
  for (std::size_t n = *to; n != *from; n = parent[n]) path.push_back(via[n]);
  Pose2 m;
  for (auto it = path.rbegin(); it != path.rend(); ++it) {
    const Pose2& r = relations_[(*it)->relation].motion;
    m = m * ((*it)->forward ? r : r.inverse());
  }
  return Truth{m, path.size()};
}

std::vector<double> RelationGraph::endpoints_near(double t, double window) const {
  std::vector<double> out;
  if (!std::isfinite(t) || !(window >= 0.0)) return out;
  const auto lo = std::lower_bound(node_times_.begin(), node_times_.end(), t - window);
  const auto hi = std::upper_bound(node_times_.begin(), node_times_.end(), t + window);
  out.assign(lo, hi);
  std::stable_sort(out.begin(), out.end(), [t](double x, double y) { return std::abs(x - t) < std::abs(y - t); });
  return out;
}

}  // namespace dsswarm
