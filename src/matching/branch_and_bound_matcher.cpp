#include "matching/branch_and_bound_matcher.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <numbers>

#include "grid/sampling.hpp"

namespace dsswarm {
namespace {
// Values are occupied − free in [-1, 1] stored as bytes: 0 ↔ -1, 255 ↔ 1.
constexpr float kZero = 127.5f;
constexpr std::uint8_t kUnknown = BranchAndBoundMatcher::kUnknownByte;
double to_score(double mean_byte) { return mean_byte / kZero - 1.0; }

// out[i] = max(in[i - s], in[i]) for i in [0, n + s), values outside [0, n) unknown.
void max_pairs(const std::uint8_t* in, std::int32_t n, std::int32_t s, std::uint8_t* out) {
  const std::int32_t both = std::min(n, s);  // [0, both): only in[i] is inside
  for (std::int32_t i = 0; i < both; ++i) out[i] = std::max(kUnknown, in[i]);
  for (std::int32_t i = both; i < s; ++i) out[i] = kUnknown;  // neither (n < s)
  for (std::int32_t i = s; i < n; ++i) out[i] = std::max(in[i - s], in[i]);
  for (std::int32_t i = std::max(n, s); i < n + s; ++i) out[i] = std::max(in[i - s], kUnknown);
}

// out[i] = max(a[i], b[i]), a missing row reading as unknown.
void max_rows(const std::uint8_t* a, const std::uint8_t* b, std::int32_t n, std::uint8_t* out) {
  // One loop per case, each simple enough to vectorize.
  if (a && b) {
    for (std::int32_t i = 0; i < n; ++i) out[i] = std::max(a[i], b[i]);
  } else if (a || b) {
    const std::uint8_t* one = a ? a : b;
    for (std::int32_t i = 0; i < n; ++i) out[i] = std::max(one[i], kUnknown);
  } else {
    std::fill(out, out + n, kUnknown);
  }
}
}  // namespace

void BranchAndBoundMatcher::double_into(const Level& prev, std::int32_t s, Level& next) {
  // The block of 2s cells starting at a cell is the four blocks of s starting
  // at it and s cells further along x, y and both: a maximum along x, then
  // along y. It reaches s cells further down-left than the level before.
  // Every value is written, so the buffers are only grown, never cleared.
  const std::int32_t w = prev.width, h = prev.height;
  along_x_.resize(std::max(along_x_.size(), static_cast<std::size_t>(w + s) * static_cast<std::size_t>(h)));
  const auto row = [](auto* v, std::int32_t y, std::int32_t width) { return v + static_cast<std::ptrdiff_t>(y) * width; };
  for (std::int32_t y = 0; y < h; ++y) max_pairs(row(prev.values.data(), y, w), w, s, row(along_x_.data(), y, w + s));
  next.origin = {prev.origin.x - s, prev.origin.y - s};
  next.width = w + s;
  next.height = h + s;
  next.values.resize(static_cast<std::size_t>(next.width) * static_cast<std::size_t>(next.height));
  for (std::int32_t y = 0; y < h + s; ++y)
    max_rows(y - s >= 0 && y - s < h ? row(along_x_.data(), y - s, w + s) : nullptr,
             y < h ? row(along_x_.data(), y, w + s) : nullptr, w + s, row(next.values.data(), y, w + s));
}

BranchAndBoundMatcher::BranchAndBoundMatcher(const DsGrid& grid, double max_window_xy, int max_depth,
                                             std::optional<CellIndex> region_min, std::optional<CellIndex> region_max) {
  rebuild(grid, max_window_xy, max_depth, region_min, region_max);
}

void BranchAndBoundMatcher::rebuild(const DsGrid& grid, double max_window_xy, int max_depth,
                                    std::optional<CellIndex> region_min, std::optional<CellIndex> region_max) {
  resolution_ = grid.resolution();
  // Blocks of 2^(depth-1) cells at the top cover the window's 2w/res + 1 offsets.
  const double offsets = 2.0 * max_window_xy / resolution_ + 1.0;
  const int depth = std::clamp(1 + static_cast<int>(std::ceil(std::log2(std::max(1.0, offsets)))), 1, max_depth);
  CellIndex lo, hi;
  grid.bounds(lo, hi);
  if (region_min) lo = {std::max(lo.x, region_min->x), std::max(lo.y, region_min->y)};
  if (region_max) hi = {std::min(hi.x, region_max->x), std::min(hi.y, region_max->y)};
  hi = {std::max(hi.x, lo.x), std::max(hi.y, lo.y)};
  levels_.resize(static_cast<std::size_t>(depth));
  Level& base = levels_.front();
  base.origin = lo;
  base.width = hi.x - lo.x;
  base.height = hi.y - lo.y;
  base.values.assign(static_cast<std::size_t>(base.width) * static_cast<std::size_t>(base.height), kUnknown);
  grid.for_each_tile([&](CellIndex origin, const PackedMass* cells) {
    // The tile's cells within [lo, hi), row by row.
    const std::int32_t x0 = std::max(lo.x, origin.x), x1 = std::min(hi.x, origin.x + DsGrid::kTileSize);
    const std::int32_t y0 = std::max(lo.y, origin.y), y1 = std::min(hi.y, origin.y + DsGrid::kTileSize);
    for (std::int32_t y = y0; y < y1; ++y) {
      const PackedMass* row = cells + DsGrid::local_index({0, y});
      std::uint8_t* out = base.values.data() + static_cast<std::ptrdiff_t>(y - lo.y) * base.width;
      for (std::int32_t x = x0; x < x1; ++x) {
        const DsMass m = row[x - origin.x].mass();
        out[x - lo.x] = static_cast<std::uint8_t>(kZero * (1.0f + m.occupied - m.free) + 0.5f);
      }
    }
  });
  // Level h (blocks of 2^h cells) from level h-1 by doubling.
  for (std::size_t h = 1; h < levels_.size(); ++h) double_into(levels_[h - 1], std::int32_t{1} << (h - 1), levels_[h]);
}

std::size_t BranchAndBoundMatcher::memory_bytes() const {
  std::size_t n = 0;
  for (const Level& l : levels_) n += l.values.capacity();
  return n + along_x_.capacity();
}

// One match call: the scan discretized per heading, and the depth-first search.
struct BranchAndBoundMatcher::Search {
  const BranchAndBoundMatcher& matcher;
  std::vector<std::vector<CellIndex>> cells;  // per heading: the points' cells at the prior translation
  std::vector<double> headings;               // per heading: θ offset from the prior
  std::vector<float> weights;
  double weight_sum = 0.0;
  std::int32_t half_window = 0;  // offsets from -half_window to +half_window cells
  Pose2 prior;
  std::optional<Pose2> exclude;
  double exclude_xy = 0.0, exclude_theta = 0.0;

  struct Candidate {
    int heading;
    std::int32_t x, y;  // offset (cells) of the block's lower-left translation
    double score;
  };

  // Per level and heading, each point's place in the level's values at offset
  // 0, and per heading the box of its points' cells: a candidate whose box
  // lands inside a level reads it without bounds checks (most do; those near
  // the edge of the searched region are checked point by point). One buffer,
  // level-major, points.size() entries per (level, heading); an entry is
  // read only when its candidate lies inside the level, where 32 bits suffice.
  std::vector<std::int32_t> index;
  std::vector<CellIndex> box_lo, box_hi;         // per heading

  void index_levels() {
    for (const std::vector<CellIndex>& heading : cells) {
      CellIndex lo{std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::max()};
      CellIndex hi{std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::min()};
      for (const CellIndex& c : heading) {
        lo = {std::min(lo.x, c.x), std::min(lo.y, c.y)};
        hi = {std::max(hi.x, c.x), std::max(hi.y, c.y)};
      }
      box_lo.push_back(lo);
      box_hi.push_back(hi);
    }
    const std::size_t n = cells.empty() ? 0 : cells.front().size();
    index.resize(matcher.levels_.size() * cells.size() * n);
    std::int32_t* out = index.data();
    for (const Level& l : matcher.levels_)
      for (const std::vector<CellIndex>& heading : cells)
        for (const CellIndex& c : heading)
          *out++ = static_cast<std::int32_t>(static_cast<std::int64_t>(c.y - l.origin.y) * l.width + (c.x - l.origin.x));
  }

  double score(const Candidate& c, int level) const {
    const Level& l = matcher.levels_[static_cast<std::size_t>(level)];
    const auto h = static_cast<std::size_t>(c.heading);
    const CellIndex lo = box_lo[h], hi = box_hi[h];
    double sum = 0.0;
    if (lo.x + c.x >= l.origin.x && lo.y + c.y >= l.origin.y && hi.x + c.x < l.origin.x + l.width &&
        hi.y + c.y < l.origin.y + l.height) {
      const std::size_t n = cells[h].size();
      const std::int32_t* at = index.data() + (static_cast<std::size_t>(level) * cells.size() + h) * n;
      const std::int64_t offset = static_cast<std::int64_t>(c.y) * l.width + c.x;
      const std::uint8_t* values = l.values.data();
      // Four sums in turn, so that each addition need not wait for the one
      // before; the products are exact in double, so are the sums (the same
      // score to the bit).
      std::array<double, 4> part{};
      const std::size_t n4 = n - n % 4;
      for (std::size_t i = 0; i < n4; i += 4)
        for (std::size_t k = 0; k < 4; ++k) part[k] += weights[i + k] * values[at[i + k] + offset];
      for (std::size_t i = n4; i < n; ++i) part[0] += weights[i] * values[at[i] + offset];
      sum = (part[0] + part[1]) + (part[2] + part[3]);
    } else {
      const std::vector<CellIndex>& pts = cells[h];
      for (std::size_t i = 0; i < pts.size(); ++i) sum += weights[i] * l.at(pts[i].x + c.x, pts[i].y + c.y);
    }
    return to_score(sum / weight_sum);
  }
  Pose2 pose_of(const Candidate& c) const {
    const double r = matcher.resolution_;
    return {prior.x + c.x * r, prior.y + c.y * r, prior.theta + headings[static_cast<std::size_t>(c.heading)]};
  }
  bool excluded(const Candidate& c) const {
    if (!exclude) return false;
    const Pose2 p = pose_of(c);
    return std::hypot(p.x - exclude->x, p.y - exclude->y) < exclude_xy &&
           std::abs(normalize_angle(p.theta - exclude->theta)) < exclude_theta;
  }

  // Children of `c` (a block at `level`), scored at level - 1, best first.
  struct Children {
    std::array<Candidate, 4> at;
    std::size_t size = 0;
  };
  Children children(const Candidate& c, int level) const {
    const std::int32_t s = 1 << (level - 1);
    Children out;
    for (std::int32_t dy : {0, s})
      for (std::int32_t dx : {0, s}) {
        Candidate k{c.heading, c.x + dx, c.y + dy, 0.0};
        if (k.x > half_window || k.y > half_window) continue;
        k.score = score(k, level - 1);
        out.at[out.size++] = k;
      }
    // Best first, ties in the order made (an insertion sort, as std::sort does for so few).
    for (std::size_t i = 1; i < out.size; ++i)
      for (std::size_t j = i; j > 0 && out.at[j].score > out.at[j - 1].score; --j) std::swap(out.at[j], out.at[j - 1]);
    return out;
  }

  void descend(const Candidate& c, int level, Candidate& best) const {
    if (c.score <= best.score) return;
    if (level == 0) {
      if (!excluded(c)) best = c;
      return;
    }
    const Children next = children(c, level);
    for (std::size_t i = 0; i < next.size; ++i) {
      if (next.at[i].score <= best.score) break;  // sorted: none after it can do better
      descend(next.at[i], level - 1, best);
    }
  }
};

double BranchAndBoundMatcher::heading_step(const std::vector<ScanPoint>& points) const {
  double max_range = 0.0;
  for (const ScanPoint& p : points)
    max_range = std::max(max_range, std::hypot(static_cast<double>(p.x), static_cast<double>(p.y)));
  // Law of cosines: the rotation that moves a point at max_range by one cell.
  return max_range > resolution_ ? std::acos(1.0 - resolution_ * resolution_ / (2.0 * max_range * max_range))
                                 : std::numbers::pi;
}

double BranchAndBoundMatcher::score(const std::vector<ScanPoint>& points, const Pose2& pose) const {
  const PointTransform to_world(pose);
  const double inv = 1.0 / resolution_;
  double sum = 0.0, weights = 0.0;
  for (const ScanPoint& p : points) {
    const Eigen::Vector2d w = to_world(p.x, p.y);
    sum += p.weight * levels_.front().at(static_cast<std::int32_t>(std::floor(w.x() * inv)),
                                         static_cast<std::int32_t>(std::floor(w.y() * inv)));
    weights += p.weight;
  }
  return weights > 0.0 ? to_score(sum / weights) : 0.0;
}

std::optional<BranchAndBoundResult> BranchAndBoundMatcher::match(const std::vector<ScanPoint>& points,
                                                                 const Pose2& prior, const SearchWindow& window,
                                                                 double min_score, const std::optional<Pose2>& exclude,
                                                                 double exclude_xy, double exclude_theta) const {
  if (points.empty()) return std::nullopt;
  Search search{*this, {}, {}, {}, 0.0, 0, prior, exclude, exclude_xy, exclude_theta, {}, {}, {}};
  for (const ScanPoint& p : points) {
    search.weights.push_back(p.weight);
    search.weight_sum += p.weight;
  }
  if (!(search.weight_sum > 0.0)) return std::nullopt;
  const double step = heading_step(points);
  const int steps = static_cast<int>(std::ceil(window.theta / step));
  const double inv = 1.0 / resolution_;
  for (int k = -steps; k <= steps; ++k) {
    const double dtheta = k * step;
    const PointTransform to_world(Pose2(prior.x, prior.y, prior.theta + dtheta));
    std::vector<CellIndex> cells;
    cells.reserve(points.size());
    for (const ScanPoint& p : points) {
      const Eigen::Vector2d w = to_world(p.x, p.y);
      cells.push_back({floor_to_cell(w.x() * inv), floor_to_cell(w.y() * inv)});
    }
    search.cells.push_back(std::move(cells));
    search.headings.push_back(dtheta);
  }
  const int max_level = depth() - 1;
  search.half_window = static_cast<std::int32_t>(std::ceil(window.xy * inv));
  search.index_levels();
  const std::int32_t block = 1 << max_level;
  std::vector<Search::Candidate> top;
  for (int h = 0; h < static_cast<int>(search.headings.size()); ++h)
    for (std::int32_t y = -search.half_window; y <= search.half_window; y += block)
      for (std::int32_t x = -search.half_window; x <= search.half_window; x += block) {
        Search::Candidate c{h, x, y, 0.0};
        c.score = search.score(c, max_level);
        top.push_back(c);
      }
  std::sort(top.begin(), top.end(), [](const auto& a, const auto& b) { return a.score > b.score; });
  Search::Candidate best{0, 0, 0, min_score};  // beaten only by poses scoring more
  for (const Search::Candidate& c : top) {
    if (c.score <= best.score) break;
    search.descend(c, max_level, best);
  }
  if (!(best.score > min_score)) return std::nullopt;
  return BranchAndBoundResult{search.pose_of(best), best.score};
}

}  // namespace dsswarm
