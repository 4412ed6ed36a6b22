#include "slam/pose_graph.hpp"

#include <algorithm>

#include <ceres/ceres.h>

#include <array>
#include <memory>
#include <utility>
#include <numbers>

#include "common/errors.hpp"

namespace dsswarm {

void PoseGraphConfig::validate() const {
  if (!(local_sigma_xy > 0.0) || !(local_sigma_theta > 0.0) || !(loop_sigma_xy > 0.0) || !(loop_sigma_theta > 0.0))
    throw ConfigError("graph.local_sigma_xy/theta and graph.loop_sigma_xy/theta must be > 0");
  if (!(foreign_sigma_xy > 0.0) || !(foreign_sigma_theta > 0.0))
    throw ConfigError("graph.foreign_sigma_xy and graph.foreign_sigma_theta must be > 0");
  if (!(loop_huber > 0.0)) throw ConfigError("graph.loop_huber must be > 0");
  if (!(peer_weight >= 0.0 && peer_weight <= 10.0)) throw ConfigError("graph.peer_weight must be in [0, 10]");
  if (max_iterations < 1) throw ConfigError("graph.max_iterations must be >= 1");
}

namespace {

template <typename T>
T wrapped(T a) {
  const T two_pi = T(2.0 * std::numbers::pi);
  while (a > T(std::numbers::pi)) a -= two_pi;
  while (a < T(-std::numbers::pi)) a += two_pi;
  return a;
}

// Residual of a relative-pose measurement z of a node in a submap's frame:
// (submap⁻¹ ⊕ node) ⊖ z, scaled by the inverse standard deviations.
struct RelativePoseError {
  Pose2 z;
  double weight_xy, weight_theta;

  template <typename T>
  bool operator()(const T* from, const T* to, T* residual) const {
    const T c = cos(from[2]), s = sin(from[2]);
    const T dx = to[0] - from[0], dy = to[1] - from[1];
    residual[0] = weight_xy * (c * dx + s * dy - z.x);
    residual[1] = weight_xy * (-s * dx + c * dy - z.y);
    residual[2] = weight_theta * wrapped(to[2] - from[2] - T(z.theta));
    return true;
  }
};

// The same with the node given in a frame: (submap⁻¹ ⊕ frame ⊕ node) ⊖ z.
struct PeerPoseError {
  Pose2 node;
  Pose2 z;
  double weight_xy, weight_theta;

  template <typename T>
  bool operator()(const T* submap, const T* frame, T* residual) const {
    const T c = cos(frame[2]), s = sin(frame[2]);
    const T to[3] = {frame[0] + c * node.x - s * node.y, frame[1] + s * node.x + c * node.y, frame[2] + T(node.theta)};
    return RelativePoseError{z, weight_xy, weight_theta}(submap, to, residual);
  }
};

using Block = std::array<double, 3>;

std::pair<double, double> sigmas(Constraint::Kind kind, const PoseGraphConfig& config) {
  switch (kind) {
    case Constraint::Kind::local: return {config.local_sigma_xy, config.local_sigma_theta};
    case Constraint::Kind::loop: return {config.loop_sigma_xy, config.loop_sigma_theta};
    case Constraint::Kind::foreign: return {config.foreign_sigma_xy, config.foreign_sigma_theta};
  }
  return {config.loop_sigma_xy, config.loop_sigma_theta};
}

Block block_of(const Pose2& p) { return {p.x, p.y, p.theta}; }

}  // namespace

const Pose2& reference_pose(const PoseGraph& graph, const Constraint& c) {
  const auto i = static_cast<std::size_t>(c.submap);
  return c.kind == Constraint::Kind::foreign ? graph.frames[i] : graph.submaps[i];
}

Pose2 constraint_error(const PoseGraph& graph, const Constraint& c) {
  return between(c.relative, between(reference_pose(graph, c), graph.nodes[static_cast<std::size_t>(c.node)]));
}

namespace {

enum class Part { all, own, frames };

// Nodes only meet submaps and frames: eliminated first, they leave a small
// system in those. Said outright, since Ceres otherwise searches the graph
// for an independent set on every solve (a third of a solve's time).
ceres::Solver::Options solver_options(const ceres::Problem& problem, Part part, std::vector<Block>& nodes,
                                      std::vector<Block>& submaps, std::vector<Block>& frames) {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_SCHUR;
  if (part == Part::frames) return options;
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (Block& b : nodes)
    if (problem.HasParameterBlock(b.data())) ordering->AddElementToGroup(b.data(), 0);
  for (std::vector<Block>* blocks : {&submaps, &frames})
    for (Block& b : *blocks)
      if (problem.HasParameterBlock(b.data())) ordering->AddElementToGroup(b.data(), 1);
  options.linear_solver_ordering = ordering;
  return options;
}

// Solves for the poses the constraints of `part` reach: all of them; this
// robot's own (no foreign constraints); or the frames alone, nodes held.
OptimizationSummary solve(PoseGraph& graph, const PoseGraphConfig& config, Part part) {
  OptimizationSummary summary;
  std::vector<Block> nodes, submaps, frames;
  for (const Pose2& p : graph.nodes) nodes.push_back(block_of(p));
  for (const Pose2& p : graph.submaps) submaps.push_back(block_of(p));
  for (const Pose2& p : graph.frames) frames.push_back(block_of(p));

  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  ceres::HuberLoss huber(config.loop_huber);
  for (const Constraint& c : graph.constraints) {
    const bool foreign = c.kind == Constraint::Kind::foreign;
    if ((part == Part::own && foreign) || (part == Part::frames && !foreign)) continue;
    const auto [sigma_xy, sigma_theta] = sigmas(c.kind, config);
    auto* cost = new ceres::AutoDiffCostFunction<RelativePoseError, 3, 3, 3>(
        new RelativePoseError{c.relative, 1.0 / sigma_xy, 1.0 / sigma_theta});
    const bool robust = c.kind != Constraint::Kind::local;
    const auto i = static_cast<std::size_t>(c.submap);
    double* reference = foreign ? frames[i].data() : submaps[i].data();
    double* node = nodes[static_cast<std::size_t>(c.node)].data();
    problem.AddResidualBlock(cost, robust ? &huber : nullptr, reference, node);
    if (part == Part::frames) problem.SetParameterBlockConstant(node);
  }
  const double peer_w_xy = config.peer_weight / config.foreign_sigma_xy;
  const double peer_w_theta = config.peer_weight / config.foreign_sigma_theta;
  if (part != Part::own && config.peer_weight > 0.0)
    for (const PeerConstraint& c : graph.peer) {
      const auto i = static_cast<std::size_t>(c.submap), f = static_cast<std::size_t>(c.frame);
      if (i >= submaps.size() || f >= frames.size()) continue;
      auto* cost = new ceres::AutoDiffCostFunction<PeerPoseError, 3, 3, 3>(
          new PeerPoseError{c.node, c.relative, peer_w_xy, peer_w_theta});
      problem.AddResidualBlock(cost, &huber, submaps[i].data(), frames[f].data());
      if (part == Part::frames) problem.SetParameterBlockConstant(submaps[i].data());
    }
  if (problem.NumResidualBlocks() == 0) return summary;
  // One submap held fixed anchors the global frame.
  if (graph.fixed_submap >= 0 && static_cast<std::size_t>(graph.fixed_submap) < submaps.size()) {
    double* fixed = submaps[static_cast<std::size_t>(graph.fixed_submap)].data();
    if (problem.HasParameterBlock(fixed)) problem.SetParameterBlockConstant(fixed);
  }

  ceres::Solver::Options options = solver_options(problem, part, nodes, submaps, frames);
  options.num_threads = 1;  // deterministic, and the caller decides where it runs
  options.max_num_iterations = config.max_iterations;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary report;
  ceres::Solve(options, &problem, &report);
  summary.iterations = static_cast<int>(report.iterations.size());
  summary.initial_cost = report.initial_cost;
  summary.final_cost = report.final_cost;
  summary.usable = report.IsSolutionUsable();
  if (!summary.usable) return summary;
  for (std::size_t i = 0; i < nodes.size(); ++i) graph.nodes[i] = {nodes[i][0], nodes[i][1], nodes[i][2]};
  for (std::size_t i = 0; i < submaps.size(); ++i) graph.submaps[i] = {submaps[i][0], submaps[i][1], submaps[i][2]};
  for (std::size_t i = 0; i < frames.size(); ++i) graph.frames[i] = {frames[i][0], frames[i][1], frames[i][2]};
  return summary;
}

}  // namespace

OptimizationSummary optimize(PoseGraph& graph, const PoseGraphConfig& config) {
  if (graph.nodes.empty()) return {};
  const bool foreign = !graph.peer.empty() ||
                       std::any_of(graph.constraints.begin(), graph.constraints.end(),
                                   [](const Constraint& c) { return c.kind == Constraint::Kind::foreign; });
  if (config.foreign_moves_own || !foreign) return solve(graph, config, Part::all);
  OptimizationSummary own = solve(graph, config, Part::own);
  if (!own.usable) return own;
  const OptimizationSummary placed = solve(graph, config, Part::frames);
  own.iterations += placed.iterations;
  own.initial_cost += placed.initial_cost;
  own.final_cost += placed.final_cost;
  own.usable = placed.usable;
  return own;
}

}  // namespace dsswarm
