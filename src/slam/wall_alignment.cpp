#include "slam/wall_alignment.hpp"

#include <cmath>
#include <numbers>

#include "common/errors.hpp"

namespace dsswarm {

namespace {

constexpr double kQuarter = std::numbers::pi / 2.0;

// `a` modulo 90°, in (-45°, 45°].
double wrap_quarter(double a) {
  a = std::remainder(a, kQuarter);
  return a <= -kQuarter / 2.0 ? a + kQuarter : a;
}

}  // namespace

void WallAlignConfig::validate() const {
  if (!(min_consistency >= 0.0 && min_consistency <= 1.0))
    throw ConfigError("slam.align_min_consistency must be in [0, 1]");
  if (!(inlier_angle > 0.0 && inlier_angle <= kQuarter / 2.0))
    throw ConfigError("slam.align_inlier_angle must be in (0, pi/4] rad");
  if (min_normals < 2) throw ConfigError("slam.align_min_normals must be >= 2");
}

std::optional<double> wall_axis(const std::vector<Eigen::Vector2d>& normals, const WallAlignConfig& config) {
  if (!config.enabled || static_cast<int>(normals.size()) < config.min_normals) return std::nullopt;
  // Four times the angle folds a normal, its opposite and the two at right
  // angles onto one direction; their mean is the walls' axis.
  double c = 0.0, s = 0.0;
  for (const Eigen::Vector2d& n : normals) {
    const double a = 4.0 * std::atan2(n.y(), n.x());
    c += std::cos(a);
    s += std::sin(a);
  }
  const double count = static_cast<double>(normals.size());
  if (std::hypot(c, s) / count < config.min_consistency) return std::nullopt;
  const double coarse = std::atan2(s, c) / 4.0;
  // Refined on the normals near it only: walls at other angles would bias the mean.
  double sum = 0.0;
  int inliers = 0;
  for (const Eigen::Vector2d& n : normals) {
    const double off = wrap_quarter(std::atan2(n.y(), n.x()) - coarse);
    if (std::abs(off) > config.inlier_angle) continue;
    sum += off;
    ++inliers;
  }
  if (inliers < config.min_normals) return std::nullopt;
  return wrap_quarter(coarse + sum / inliers);
}

Pose2 turned_to_walls(const Pose2& start, double axis) {
  return Pose2(start.x, start.y, start.theta + wrap_quarter(-(axis + start.theta)));
}

}  // namespace dsswarm
