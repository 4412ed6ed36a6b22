#include "grid/map_combine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/errors.hpp"
#include "grid/sampling.hpp"

namespace dsswarm {
namespace {

constexpr float kNothing = 1e-4f;  // below this a source cell knows nothing

void check_compatible(const MultiResMap& target, const MultiResMap& source) {
  if (source.levels() != target.levels() || source.config().resolution != target.config().resolution)
    throw ConfigError("cannot merge maps of different resolution or levels (" +
                      std::to_string(source.config().resolution) + " m × " + std::to_string(source.levels()) +
                      " vs " + std::to_string(target.config().resolution) + " m × " +
                      std::to_string(target.levels()) + ")");
}

void combine_level(DsGrid& target, const DsGrid& source, const Pose2& source_in_target, const EvidenceModel& evidence) {
  CellIndex smin, smax;
  source.bounds(smin, smax);
  if (smin == smax) return;
  // The source's extent, placed in the target frame, bounds the cells to visit.
  const double sr = source.resolution();
  double lo_x = std::numeric_limits<double>::max(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
  for (int corner = 0; corner < 4; ++corner) {
    const Eigen::Vector2d p((corner & 1 ? smax.x : smin.x) * sr, (corner & 2 ? smax.y : smin.y) * sr);
    const Eigen::Vector2d q = source_in_target * p;
    lo_x = std::min(lo_x, q.x());
    lo_y = std::min(lo_y, q.y());
    hi_x = std::max(hi_x, q.x());
    hi_y = std::max(hi_y, q.y());
  }
  const CellIndex tmin = target.cell_of({lo_x, lo_y}), tmax = target.cell_of({hi_x, hi_y});
  const Pose2 target_in_source = source_in_target.inverse();
  const PointTransform to_source(target_in_source);
  const double tr = target.resolution();
  for (std::int32_t y = tmin.y; y <= tmax.y; ++y) {
    const double wy = (y + 0.5) * tr;
    for (std::int32_t x = tmin.x; x <= tmax.x; ++x) {
      const double wx = (x + 0.5) * tr;
      const Eigen::Vector2d sp = to_source(wx, wy);
      const DsMass m = interpolated_masses(source, sp.x(), sp.y());
      if (m.occupied + m.free < kNothing) continue;
      DsMass& cell = target.mutable_at({x, y});
      cell = evidence.update(cell, m);
    }
  }
}

}  // namespace

void combine_into(MultiResMap& target, const MultiResMap& source, const Pose2& source_in_target) {
  check_compatible(target, source);
  for (int level = 0; level < target.levels(); ++level)
    combine_level(target.mutable_level(level), source.level(level), source_in_target, target.config().evidence);
}

void combine_aligned(MultiResMap& target, const MultiResMap& source) {
  check_compatible(target, source);
  const EvidenceModel& evidence = target.config().evidence;
  for (int level = 0; level < target.levels(); ++level) {
    DsGrid& t = target.mutable_level(level);
    source.level(level).for_each_tile([&](CellIndex origin, const DsMass* cells) {
      for (int i = 0; i < DsGrid::kTileCells; ++i) {
        if (cells[i].occupied + cells[i].free < kNothing) continue;
        DsMass& cell = t.mutable_at(DsGrid::tile_cell(origin, i));
        cell = evidence.update(cell, cells[i]);
      }
    });
  }
}

}  // namespace dsswarm
