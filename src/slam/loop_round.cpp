#include "slam/loop_round.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "matching/branch_and_bound_matcher.hpp"

namespace dsswarm {
namespace {

struct Task {
  int node;
  int submap;
  SearchWindow window;
  const CompactScan* points;
  Pose2 prior;  // the node's estimated pose in the submap's cells (the local frame)
};

Pose2 prior_in(const RoundInput& in, int node, int submap) {
  return in.submaps[static_cast<std::size_t>(submap)].anchor *
         between(in.graph.submaps[static_cast<std::size_t>(submap)], in.graph.nodes[static_cast<std::size_t>(node)]);
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

// Wider the further the robot went since the submap or the last closure.
SearchWindow window_for(const RoundInput& in, int node, int submap, const LoopClosureConfig& config) {
  const double since = std::max(in.submaps[static_cast<std::size_t>(submap)].travel_end, in.last_closure_travel);
  const double d = std::max(0.0, in.node_travel[static_cast<std::size_t>(node)] - since);
  return {std::min(config.max_window_xy, config.window_xy + config.window_xy_per_m * d),
          std::min(config.max_window_theta, config.window_theta + config.window_theta_per_m * d)};
}

void count_rejection(LoopClosureStats& stats, LoopRejection r) {
  switch (r) {
    case LoopRejection::none: ++stats.candidates; break;
    case LoopRejection::no_match: ++stats.rejected_no_match; break;
    case LoopRejection::unknown: ++stats.rejected_unknown; break;
    case LoopRejection::inliers: ++stats.rejected_inliers; break;
    case LoopRejection::same_side: ++stats.rejected_same_side; break;
    case LoopRejection::ambiguous: ++stats.rejected_ambiguous; break;
  }
}

Constraint as_constraint(const LoopCandidate& c) { return {Constraint::Kind::loop, c.submap, c.node, c.relative}; }

std::vector<LoopCandidate> search_all(const RoundInput& in, const LoopClosureConfig& config,
                                      const PointWeightConfig& weights, std::uint64_t seed, LoopClosureStats& stats) {
  std::vector<Task> tasks;
  // Per submap: the widest window asked of it, and the cells its searches can reach.
  struct Reach {
    double window = 0.0;
    CellIndex lo{std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::max()};
    CellIndex hi{std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::min()};
  };
  std::map<int, Reach> reach;
  const double inv = 1.0 / in.map.resolution;
  for (const RoundInput::Search& s : in.searches)
    for (int submap : nearby_submaps(in, s.node, config)) {
      Task t{s.node, submap, window_for(in, s.node, submap, config), s.points.get(), prior_in(in, s.node, submap)};
      Reach& r = reach[submap];
      r.window = std::max(r.window, t.window.xy);
      const double extent = t.window.xy + config.search.max_range + in.map.resolution;
      const auto cell = [&](double v) { return static_cast<std::int32_t>(std::floor(v * inv)); };
      r.lo = {std::min(r.lo.x, cell(t.prior.x - extent)), std::min(r.lo.y, cell(t.prior.y - extent))};
      r.hi = {std::max(r.hi.x, cell(t.prior.x + extent) + 1), std::max(r.hi.y, cell(t.prior.y + extent) + 1)};
      tasks.push_back(t);
    }
  // Submap by submap, so each one's bounds are built once and freed after.
  std::stable_sort(tasks.begin(), tasks.end(), [](const Task& a, const Task& b) { return a.submap < b.submap; });
  std::vector<LoopCandidate> found;
  MapConfig finest_only = in.map;
  finest_only.levels = 1;
  std::unique_ptr<BranchAndBoundMatcher> matcher;
  std::optional<Submap> thawed;  // the submap searched now, as a live map
  int matcher_submap = -1;
  for (const Task& t : tasks) {
    const RoundInput::SubmapInfo& info = in.submaps[static_cast<std::size_t>(t.submap)];
    if (t.submap != matcher_submap) {
      // The finest level around the searched poses is all a search needs:
      // branch and bound places the scan within a cell, the refinement only
      // polishes, both with the points within max_range.
      thawed = Submap{info.finished->id, info.finished->anchor, info.finished->scans, info.finished->travel, false,
                      info.finished->frozen.thaw(finest_only, reach[t.submap].lo, reach[t.submap].hi),
                      FrozenMap()};
      const Reach& r = reach[t.submap];
      matcher = std::make_unique<BranchAndBoundMatcher>(thawed->map.finest(), r.window, config.search.max_depth, r.lo,
                                                        r.hi);
      matcher_submap = t.submap;
    }
    const std::uint64_t task_seed = seed ^ (static_cast<std::uint64_t>(t.node) * 0x9E3779B97F4A7C15ull +
                                            static_cast<std::uint64_t>(t.submap));
    LoopSearch r = search_loop_closure(*matcher, *thawed, t.points->points(weights), t.prior, t.window,
                                       config.search, task_seed);
    ++stats.searches;
    count_rejection(stats, r.rejection);
    if (r.rejection != LoopRejection::none) continue;
    r.candidate.node = t.node;
    r.candidate.submap = t.submap;
    found.push_back(r.candidate);
  }
  return found;
}

// Whether closures a and b can be compared: nodes close along the
// trajectory, submaps the same or as close.
bool comparable(const RoundInput& in, const Constraint& a, const Constraint& b, double travel) {
  const auto t = [&](int node) { return in.node_travel[static_cast<std::size_t>(node)]; };
  const auto end = [&](int s) { return in.submaps[static_cast<std::size_t>(s)].travel_end; };
  return std::abs(t(a.node) - t(b.node)) <= travel &&
         (a.submap == b.submap || std::abs(end(a.submap) - end(b.submap)) <= travel);
}

// Splits this round's candidates and the pending ones into those with an
// agreeing partner (accepted) and those without (pending, or expired).
void confirm(const RoundInput& in, std::vector<LoopCandidate> fresh, const LoopClosureConfig& config,
             RoundOutput& out) {
  std::vector<PendingCandidate> pool = in.pending;
  for (const LoopCandidate& c : fresh) pool.push_back({c, 0});
  std::vector<Constraint> accepted_before;
  for (const Constraint& c : in.graph.constraints)
    if (c.kind == Constraint::Kind::loop) accepted_before.push_back(c);
  for (std::size_t i = 0; i < pool.size(); ++i) {
    const Constraint a = as_constraint(pool[i].candidate);
    bool agreed = false;
    for (std::size_t j = 0; j < pool.size() && !agreed; ++j) {
      const Constraint b = as_constraint(pool[j].candidate);
      agreed = j != i && a.node != b.node && comparable(in, a, b, config.consistency_travel) &&
               closures_agree(in.graph, a, b, config.agree_xy, config.agree_theta);
    }
    for (std::size_t j = 0; j < accepted_before.size() && !agreed; ++j)
      agreed = a.node != accepted_before[j].node && comparable(in, a, accepted_before[j], config.consistency_travel) &&
               closures_agree(in.graph, a, accepted_before[j], config.agree_xy, config.agree_theta);
    if (agreed)
      out.accepted.push_back(pool[i].candidate);
    else if (pool[i].age < config.pending_rounds)
      out.pending.push_back({pool[i].candidate, pool[i].age + 1});
    else
      ++out.stats.rejected_inconsistent;
  }
}

// Optimizes with the accepted closures; drops, one at a time, the worst new
// closure the optimized graph does not bear out, and optimizes again.
void optimize_with(const RoundInput& in, const LoopClosureConfig& config, RoundOutput& out) {
  while (!out.accepted.empty()) {
    out.graph = in.graph;
    for (const LoopCandidate& c : out.accepted) out.graph.constraints.push_back(as_constraint(c));
    out.optimized = optimize(out.graph, config.graph).usable;
    if (!out.optimized) return;
    std::size_t worst = 0;
    double worst_excess = 0.0;
    for (std::size_t k = 0; k < out.accepted.size(); ++k) {
      const Pose2 e = constraint_error(out.graph, as_constraint(out.accepted[k]));
      const double excess = std::max(std::hypot(e.x, e.y) / config.max_residual_xy,
                                     std::abs(e.theta) / config.max_residual_theta);
      if (excess > worst_excess) {
        worst_excess = excess;
        worst = k;
      }
    }
    if (worst_excess <= 1.0) return;
    out.accepted.erase(out.accepted.begin() + static_cast<std::ptrdiff_t>(worst));
    ++out.stats.rejected_residual;
    out.optimized = false;
  }
}

}  // namespace

void run_round(Round& round, const LoopClosureConfig& config, const PointWeightConfig& weights, std::uint64_t seed) {
  const auto t0 = std::chrono::steady_clock::now();
  RoundOutput& out = round.out;
  std::vector<LoopCandidate> fresh = search_all(round.in, config, weights, seed, out.stats);
  confirm(round.in, std::move(fresh), config, out);
  out.stats.accepted = out.accepted.size();
  optimize_with(round.in, config, out);
  out.stats.accepted = out.accepted.size();
  out.stats.background_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void add_stats(LoopClosureStats& total, const LoopClosureStats& more) {
  total.searches += more.searches;
  total.candidates += more.candidates;
  total.accepted += more.accepted;
  total.rejected_no_match += more.rejected_no_match;
  total.rejected_unknown += more.rejected_unknown;
  total.rejected_inliers += more.rejected_inliers;
  total.rejected_same_side += more.rejected_same_side;
  total.rejected_ambiguous += more.rejected_ambiguous;
  total.rejected_inconsistent += more.rejected_inconsistent;
  total.rejected_residual += more.rejected_residual;
  total.background_seconds += more.background_seconds;
}

}  // namespace dsswarm
