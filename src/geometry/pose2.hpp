#pragma once
// Rigid 2D transforms (SE(2)). A Pose2 maps points from its local frame into
// the parent frame: p_parent = R(theta) * p_local + (x, y).
#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace dsswarm {

// Wraps an angle to (-pi, pi].
inline double normalize_angle(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);  // [-pi, pi]
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;  // radians, kept in (-pi, pi] by every operation

  Pose2() = default;
  Pose2(double x_, double y_, double theta_) : x(x_), y(y_), theta(normalize_angle(theta_)) {}

  // Composition: (*this) ⊕ other, i.e. `other` expressed in this pose's frame.
  Pose2 operator*(const Pose2& other) const;

  Pose2 inverse() const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {-(c * x + s * y), s * x - c * y, -theta};
  }

  Eigen::Vector2d operator*(const Eigen::Vector2d& p) const;

  Eigen::Vector2d translation() const { return {x, y}; }
  // Bit for bit the same pose (whether something moved at all, not whether it moved much).
  bool operator==(const Pose2&) const = default;
};

// A pose as a point transform with its cosine and sine computed once: the
// one implementation of p_parent = R(theta) * p_local + (x, y), for code that
// transforms many points by the same pose.
struct PointTransform {
  double c = 1.0, s = 0.0, x = 0.0, y = 0.0;

  explicit PointTransform(const Pose2& pose)
      : c(std::cos(pose.theta)), s(std::sin(pose.theta)), x(pose.x), y(pose.y) {}
  // A pure rotation by `theta` as given (not wrapped into (-pi, pi]).
  static PointTransform rotation(double theta) { return PointTransform(std::cos(theta), std::sin(theta)); }

  Eigen::Vector2d operator()(double px, double py) const { return {x + c * px - s * py, y + s * px + c * py}; }

 private:
  PointTransform(double cos_theta, double sin_theta) : c(cos_theta), s(sin_theta) {}
};

inline Eigen::Vector2d Pose2::operator*(const Eigen::Vector2d& p) const { return PointTransform(*this)(p.x(), p.y()); }

inline Pose2 Pose2::operator*(const Pose2& other) const {
  const Eigen::Vector2d t = PointTransform(*this)(other.x, other.y);
  return {t.x(), t.y(), theta + other.theta};
}

// Motion from a to b expressed in a's frame: a⁻¹ ⊕ b.
inline Pose2 between(const Pose2& a, const Pose2& b) { return a.inverse() * b; }

// Exactly the identity (a frame never moved), not merely close to it.
inline bool is_identity(const Pose2& p) { return p.x == 0.0 && p.y == 0.0 && p.theta == 0.0; }

// Linear interpolation of translation, shortest-arc interpolation of heading; t in [0, 1].
inline Pose2 interpolate(const Pose2& a, const Pose2& b, double t) {
  return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y),
          a.theta + t * normalize_angle(b.theta - a.theta)};
}

}  // namespace dsswarm
