#include "slam/degeneracy.hpp"

#include <algorithm>

#include <Eigen/Eigenvalues>

#include "common/errors.hpp"

namespace dsswarm {

void DegeneracyConfig::validate() const {
  if (!(min_ratio >= 0.0 && min_ratio < 1.0)) throw ConfigError("slam.degeneracy_min_ratio must be in [0, 1)");
  if (!(normal_radius > 0.0)) throw ConfigError("slam.degeneracy_normal_radius must be > 0");
  if (normal_neighbors < 1) throw ConfigError("slam.degeneracy_normal_neighbors must be >= 1");
  if (min_patch < 3) throw ConfigError("slam.degeneracy_min_patch must be >= 3");
  if (!(max_patch_spread > 0.0 && max_patch_spread < 1.0))
    throw ConfigError("slam.degeneracy_max_patch_spread must be in (0, 1)");
  if (min_normals < 2) throw ConfigError("slam.degeneracy_min_normals must be >= 2");
}

namespace {

// Eigenvalues ascending with their vectors, in closed form: Eigen's
// iterative solver cost more than the rest of this check (once per scan point).
Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solve_2x2(const Eigen::Matrix2d& m) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen;
  eigen.computeDirect(m);
  return eigen;
}

// The normal of the line fitted to point i's neighbourhood, if it is a line.
std::optional<Eigen::Vector2d> patch_normal(const std::vector<ScanPoint>& points, std::size_t i,
                                            const DegeneracyConfig& config) {
  const Eigen::Vector2d centre(points[i].x, points[i].y);
  const std::size_t k = static_cast<std::size_t>(config.normal_neighbors);
  const std::size_t first = i >= k ? i - k : 0, last = std::min(points.size() - 1, i + k);
  const double radius_squared = config.normal_radius * config.normal_radius;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d outer = Eigen::Matrix2d::Zero();
  int n = 0;
  for (std::size_t j = first; j <= last; ++j) {
    const Eigen::Vector2d p(points[j].x, points[j].y);
    if ((p - centre).squaredNorm() > radius_squared) continue;
    sum += p;
    outer += p * p.transpose();
    ++n;
  }
  if (n < config.min_patch) return std::nullopt;
  const Eigen::Vector2d mean = sum / n;
  const Eigen::Matrix2d covariance = outer / n - mean * mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen = solve_2x2(covariance);
  if (!(eigen.eigenvalues()(1) > 0.0) || eigen.eigenvalues()(0) > config.max_patch_spread * eigen.eigenvalues()(1))
    return std::nullopt;
  return eigen.eigenvectors().col(0);
}

// Calls `use` with each point's normal, where it has one.
template <class Use>
void for_each_normal(const std::vector<ScanPoint>& points, const DegeneracyConfig& config, Use use) {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (const std::optional<Eigen::Vector2d> normal = patch_normal(points, i, config)) use(*normal);
}

}  // namespace

std::vector<Eigen::Vector2d> surface_normals(const std::vector<ScanPoint>& points, const DegeneracyConfig& config) {
  std::vector<Eigen::Vector2d> normals;
  for_each_normal(points, config, [&](const Eigen::Vector2d& n) { normals.push_back(n); });
  return normals;
}

std::optional<Eigen::Vector2d> weak_direction(const std::vector<ScanPoint>& points, const DegeneracyConfig& config) {
  if (config.min_ratio <= 0.0) return std::nullopt;
  // Summed as they come: this runs on every matched scan, no list needed.
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  int normals = 0;
  for_each_normal(points, config, [&](const Eigen::Vector2d& n) {
    scatter += n * n.transpose();
    ++normals;
  });
  if (normals < config.min_normals) return std::nullopt;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen = solve_2x2(scatter);
  if (eigen.eigenvalues()(0) >= config.min_ratio * eigen.eigenvalues()(1)) return std::nullopt;
  return eigen.eigenvectors().col(0).normalized();
}

Pose2 hold_along(const Pose2& prior, const Pose2& matched, const Eigen::Vector2d& weak) {
  const Pose2 d = between(prior, matched);
  const Eigen::Vector2d t(d.x, d.y);
  const Eigen::Vector2d kept = t - t.dot(weak) * weak;
  return prior * Pose2(kept.x(), kept.y(), d.theta);
}

}  // namespace dsswarm
