#include "slam/loop_round.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "matching/branch_and_bound_matcher.hpp"
#include "slam/loop_tasks.hpp"

namespace dsswarm {
namespace {

using round_detail::Target;
using round_detail::Task;
using round_detail::tasks_for;

void count_rejection(LoopClosureStats& stats, LoopRejection r) {
  switch (r) {
    case LoopRejection::none: ++stats.candidates; break;
    case LoopRejection::no_match: ++stats.rejected_no_match; break;
    case LoopRejection::unknown: ++stats.rejected_unknown; break;
    case LoopRejection::inliers: ++stats.rejected_inliers; break;
    case LoopRejection::same_side: ++stats.rejected_same_side; break;
    case LoopRejection::ambiguous: ++stats.rejected_ambiguous; break;
    case LoopRejection::prior_fits: ++stats.rejected_prior_fits; break;
  }
}

Constraint as_constraint(const LoopCandidate& c) {
  return {c.foreign ? Constraint::Kind::foreign : Constraint::Kind::loop, c.submap, c.node, c.relative, c.piece,
          c.piece_pose};
}

// The cells a target's searches can reach, and the widest window asked of it.
struct Reach {
  double window = 0.0;
  CellIndex lo{std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::max()};
  CellIndex hi{std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::min()};
};

Reach reach_of(const std::vector<Task>& tasks, std::size_t first, const RoundInput& in, const LoopClosureConfig& config) {
  Reach r;
  const double inv = 1.0 / in.map.resolution;
  const auto cell = [&](double v) { return static_cast<std::int32_t>(std::floor(v * inv)); };
  for (std::size_t i = first; i < tasks.size() && tasks[i].target == tasks[first].target; ++i) {
    const Task& t = tasks[i];
    r.window = std::max(r.window, t.window.xy);
    const double extent = t.window.xy + config.search.max_range + in.map.resolution;
    r.lo = {std::min(r.lo.x, cell(t.prior.x - extent)), std::min(r.lo.y, cell(t.prior.y - extent))};
    r.hi = {std::max(r.hi.x, cell(t.prior.x + extent) + 1), std::max(r.hi.y, cell(t.prior.y + extent) + 1)};
  }
  return r;
}

// The target's finest level around the searched poses, as a live map: all a
// search needs (branch and bound places the scan within a cell, the
// refinement only polishes, both with the points within max_range).
Submap thaw_target(const RoundInput& in, const Target& target, const Reach& r) {
  MapConfig finest_only = in.map;
  finest_only.levels = 1;
  if (target.foreign) {
    const ForeignPiece& p = in.foreign[static_cast<std::size_t>(target.index)].piece;
    return Submap{p.id, Pose2(), 0, 0.0, false, p.map->thaw(finest_only, r.lo, r.hi), FrozenMap()};
  }
  const Submap& s = *in.submaps[static_cast<std::size_t>(target.index)].finished;
  return Submap{s.id, s.anchor, s.scans, s.travel, false, s.frozen.thaw(finest_only, r.lo, r.hi), FrozenMap()};
}

// Our own submaps' closures so far, by submap: the travel of each one's node.
class ClosedNearby {
 public:
  ClosedNearby(const RoundInput& in, double within) : in_(in), within_(within) {
    for (const Constraint& c : in.graph.constraints)
      if (c.kind == Constraint::Kind::loop) add(c.submap, c.node);
  }
  void add(int submap, int node) { travel_[submap].push_back(in_.node_travel[static_cast<std::size_t>(node)]); }
  bool near(const Target& t, int node) const {
    if (t.foreign || !(within_ > 0.0)) return false;
    const auto it = travel_.find(t.index);
    if (it == travel_.end()) return false;
    const double at = in_.node_travel[static_cast<std::size_t>(node)];
    return std::any_of(it->second.begin(), it->second.end(), [&](double d) { return std::abs(d - at) < within_; });
  }

 private:
  const RoundInput& in_;
  double within_;
  std::map<int, std::vector<double>> travel_;
};

std::vector<LoopCandidate> search_all(const RoundInput& in, const LoopClosureConfig& config,
                                      const PointWeightConfig& weights, std::uint64_t seed, BranchAndBoundMatcher& matcher,
                                      LoopClosureStats& stats) {
  const std::vector<Task> tasks = tasks_for(in, config);
  std::vector<LoopCandidate> found;
  std::optional<Submap> thawed;  // the target searched now
  std::optional<Target> thawed_target;
  ClosedNearby closed(in, config.reclose_travel);
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const Task& t = tasks[i];
    if (closed.near(t.target, t.node)) {
      ++stats.skipped_closed;
      continue;
    }
    if (thawed_target != t.target) {
      thawed_target = t.target;
      const Reach r = reach_of(tasks, i, in, config);
      thawed = thaw_target(in, t.target, r);
      matcher.rebuild(thawed->map.finest(), r.window, config.search.max_depth, r.lo, r.hi);
    }
    const auto target_key = static_cast<std::uint64_t>(t.target.index) + (t.target.foreign ? (1ull << 32) : 0ull);
    const std::uint64_t task_seed = seed ^ (static_cast<std::uint64_t>(t.node) * 0x9E3779B97F4A7C15ull + target_key);
    LoopSearch r = search_loop_closure(matcher, *thawed, t.points->points(weights), t.prior, t.window,
                                       config.search, task_seed);
    ++stats.searches;
    count_rejection(stats, r.rejection);
    if (r.rejection != LoopRejection::none) continue;
    r.candidate.node = t.node;
    if (t.target.foreign) {
      const ForeignPieceInfo& piece = in.foreign[static_cast<std::size_t>(t.target.index)];
      r.candidate.foreign = true;
      r.candidate.submap = piece.frame;
      r.candidate.relative = piece.piece.pose * r.candidate.relative;  // from its cells into its robot's frame
      r.candidate.piece = t.target.index;
      r.candidate.piece_pose = piece.piece.pose;
      ++stats.foreign_candidates;
    } else {
      r.candidate.submap = t.target.index;
      closed.add(t.target.index, t.node);
    }
    found.push_back(r.candidate);
  }
  return found;
}

// Whether closures a and b can be compared: nodes close along the
// trajectory, submaps the same or as close.
// Another robot's frame is one rigid map: closures into it compare wherever
// they are on it.
bool comparable(const RoundInput& in, const Constraint& a, const Constraint& b, double travel) {
  const auto t = [&](int node) { return in.node_travel[static_cast<std::size_t>(node)]; };
  const auto end = [&](int s) { return in.submaps[static_cast<std::size_t>(s)].travel_end; };
  if (std::abs(t(a.node) - t(b.node)) > travel) return false;
  const bool foreign_a = a.kind == Constraint::Kind::foreign, foreign_b = b.kind == Constraint::Kind::foreign;
  if (foreign_a || foreign_b) return foreign_a == foreign_b && a.submap == b.submap;
  return a.submap == b.submap || std::abs(end(a.submap) - end(b.submap)) <= travel;
}

// Splits this round's candidates and the pending ones into those with an
// agreeing partner (accepted) and those without (pending, or expired).
void confirm(const RoundInput& in, std::vector<LoopCandidate> fresh, const LoopClosureConfig& config,
             RoundOutput& out) {
  std::vector<PendingCandidate> pool = in.pending;
  for (const LoopCandidate& c : fresh) pool.push_back({c, 0});
  std::vector<Constraint> accepted_before;
  for (const Constraint& c : in.graph.constraints)
    if (c.kind != Constraint::Kind::local) accepted_before.push_back(c);
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
  if (out.accepted.empty() && in.new_constraints) {
    out.graph = in.graph;
    out.optimized = optimize(out.graph, config.graph).usable;
    return;
  }
  // Room for the closures up front: the copy below then keeps it, and adding
  // them does not reallocate (and copy) every constraint of the graph.
  out.graph.constraints.reserve(in.graph.constraints.size() + out.accepted.size());
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

// The graph's estimates and closures, from the state the round starts from.
void complete_input(RoundInput& in, const LoopState& start) {
  PoseGraph& g = in.graph;
  g.nodes.resize(in.node_local.size());
  for (std::size_t i = 0; i < g.nodes.size(); ++i)
    g.nodes[i] = i < start.nodes.size() ? start.nodes[i] : start.global_from_local * in.node_local[i];
  g.submaps.resize(in.submaps.size());
  for (std::size_t s = 0; s < g.submaps.size(); ++s)
    g.submaps[s] = s < start.submaps.size() ? start.submaps[s] : start.global_from_local * in.submaps[s].anchor;
  for (std::size_t f = 0; f < g.frames.size() && f < start.frames.size(); ++f)
    if (in.frame_tied[f]) g.frames[f] = start.frames[f];
  g.constraints.reserve(g.constraints.size() + start.closures.size());  // exactly: not doubled
  g.constraints.insert(g.constraints.end(), start.closures.begin(), start.closures.end());
  in.pending = start.pending;
  // Other robots' pieces that moved since (their later closures): ours into them follow.
  follow_pieces(g.constraints, in.foreign);
  for (PendingCandidate& p : in.pending) follow_piece(p.candidate.piece, p.candidate.piece_pose, p.candidate.relative, in.foreign);
  in.last_closure_travel = start.last_closure_travel;
}

LoopState next_state(const LoopState& start, const RoundInput& in, const RoundOutput& out) {
  LoopState next = start;
  follow_pieces(next.closures, in.foreign);  // as the round saw them (complete_input)
  next.optimized = out.optimized;
  for (const LoopCandidate& c : out.accepted) {
    next.closures.push_back(as_constraint(c));
    if (!c.foreign)
      next.last_closure_travel = std::max(next.last_closure_travel, in.node_travel[static_cast<std::size_t>(c.node)]);
  }
  next.pending = out.pending;
  if (out.optimized && !out.graph.nodes.empty()) {
    next.nodes = out.graph.nodes;
    next.submaps = out.graph.submaps;
    next.frames = out.graph.frames;
    next.global_from_local = next.nodes.back() * in.node_local.back().inverse();
  }
  return next;
}

}  // namespace

void run_round(Round& round, const LoopClosureConfig& config, const PointWeightConfig& weights, std::uint64_t seed) {
  const auto t0 = std::chrono::steady_clock::now();
  complete_input(round.in, round.previous ? round.previous->out.state : round.base);
  RoundOutput& out = round.out;
  if (!round.scratch) round.scratch = std::make_shared<RoundScratch>();
  std::vector<LoopCandidate> fresh = search_all(round.in, config, weights, seed, round.scratch->matcher, out.stats);
  confirm(round.in, std::move(fresh), config, out);
  out.stats.accepted = out.accepted.size();
  optimize_with(round.in, config, out);
  out.stats.accepted = out.accepted.size();
  out.stats.foreign_accepted = static_cast<std::size_t>(
      std::count_if(out.accepted.begin(), out.accepted.end(), [](const LoopCandidate& c) { return c.foreign; }));
  out.state = next_state(round.previous ? round.previous->out.state : round.base, round.in, out);
  round.previous.reset();  // its state is in ours now
  out.stats.background_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void add_stats(LoopClosureStats& total, const LoopClosureStats& more) {
  total.searches += more.searches;
  total.skipped_closed += more.skipped_closed;
  total.candidates += more.candidates;
  total.accepted += more.accepted;
  total.rejected_no_match += more.rejected_no_match;
  total.rejected_unknown += more.rejected_unknown;
  total.rejected_inliers += more.rejected_inliers;
  total.rejected_same_side += more.rejected_same_side;
  total.rejected_ambiguous += more.rejected_ambiguous;
  total.rejected_prior_fits += more.rejected_prior_fits;
  total.rejected_inconsistent += more.rejected_inconsistent;
  total.rejected_residual += more.rejected_residual;
  total.foreign_candidates += more.foreign_candidates;
  total.foreign_accepted += more.foreign_accepted;
  total.background_seconds += more.background_seconds;
}

}  // namespace dsswarm
