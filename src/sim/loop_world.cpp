#include "sim/loop_world.hpp"

#include <cmath>

#include "common/errors.hpp"
#include "common/rng.hpp"

namespace dsswarm {
namespace {

// Features along one wall from a to b (unit normal `inward` into the corridor):
// a pillar or a niche every 2.5-5 m, of random size.
void furnish(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& inward, double corridor,
             Rng& rng, std::vector<Segment>& walls, std::vector<Box>& solids) {
  const Eigen::Vector2d along = (b - a).normalized();
  const double length = (b - a).norm();
  double s = 0.0;
  Eigen::Vector2d from = a;
  for (s = rng.uniform(1.5, 3.0); s < length - 1.5; s += rng.uniform(2.5, 5.0)) {
    const double w = rng.uniform(0.3, 0.8), d = rng.uniform(0.15, 0.25 * corridor);
    const Eigen::Vector2d p = a + along * s;
    if (rng.uniform() < 0.5) {  // a pillar standing out of the wall
      const Eigen::Vector2d c0 = p, c1 = p + along * w + inward * d;
      solids.push_back({c0.cwiseMin(c1), c0.cwiseMax(c1)});
      continue;
    }
    // A niche: the wall steps back by d for w metres.
    const Eigen::Vector2d q = p + along * w;
    walls.push_back({from, p});
    walls.push_back({p, p - inward * d});
    walls.push_back({p - inward * d, q - inward * d});
    walls.push_back({q - inward * d, q});
    from = q;
  }
  walls.push_back({from, b});
}

}  // namespace

LoopWorld make_loop_world(const LoopWorldConfig& c) {
  if (!(c.corridor >= 1.2) || !(c.width > 2.0 * c.corridor + 2.0) || !(c.height > 2.0 * c.corridor + 2.0))
    throw ConfigError("loop world: corridor must be >= 1.2 m and leave a block of at least 2 m inside");
  if (!(c.laps > 0.0 && c.laps <= 10.0)) throw ConfigError("loop world: laps must be in (0, 10]");
  Rng rng(c.seed);
  std::vector<Segment> walls;
  std::vector<Box> solids;
  const double w = c.width, h = c.height, k = c.corridor;
  // Outer walls (corridor inside them), counter-clockwise, each furnished towards the corridor.
  const Eigen::Vector2d o[4] = {{0, 0}, {w, 0}, {w, h}, {0, h}};
  const Eigen::Vector2d in_out[4] = {{0, 1}, {-1, 0}, {0, -1}, {1, 0}};
  for (int i = 0; i < 4; ++i) furnish(o[i], o[(i + 1) % 4], in_out[i], k, rng, walls, solids);
  // Inner block's walls, facing outwards.
  const Eigen::Vector2d n[4] = {{k, k}, {w - k, k}, {w - k, h - k}, {k, h - k}};
  const Eigen::Vector2d in_in[4] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
  for (int i = 0; i < 4; ++i) furnish(n[i], n[(i + 1) % 4], in_in[i], k, rng, walls, solids);
  // The tour: the ring's centre line, corner to corner, `laps` times.
  const double m = k / 2.0;
  const std::vector<Eigen::Vector2d> corners{{m, m}, {w - m, m}, {w - m, h - m}, {m, h - m}};
  const double lap = 2.0 * (w - k) + 2.0 * (h - k);
  LoopWorld out{World(std::move(walls), std::move(solids)), {}, Pose2(w / 2.0, m, 0.0)};
  double driven = 0.0;
  Eigen::Vector2d at = out.start.translation();
  for (int i = 1; driven < c.laps * lap; i = (i + 1) % 4) {
    const Eigen::Vector2d next = corners[static_cast<std::size_t>(i)];
    const double leg = (next - at).norm();
    if (driven + leg > c.laps * lap) {
      out.tour.push_back(at + (next - at) * ((c.laps * lap - driven) / leg));
      break;
    }
    out.tour.push_back(next);
    driven += leg;
    at = next;
  }
  return out;
}

}  // namespace dsswarm
