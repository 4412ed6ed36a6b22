#pragma once
// Were the obstacles a placed scan lands on seen from the same side? A thin
// wall seen from opposite sides fits either way when shifted by its
// thickness, and scores alone cannot tell the two apart: of the points that
// land on obstacles, the weight share whose beam, once clear of the obstacle
// (15 cm or more before the hit), runs through space the map has seen free.
// Used wherever a scan is placed in a map it was not matched into step by
// step: another robot's scan at an encounter, a loop closure.
#include <vector>

#include "geometry/pose2.hpp"
#include "grid/ds_grid.hpp"
#include "sensor/scan_points.hpp"

namespace dsswarm {

// The same-side ratio of `points` (robot base frame) placed at `pose`, in [0, 1]
// (0 when no point lands on an obstacle).
double same_side_ratio(const DsGrid& grid, const std::vector<ScanPoint>& points, const Pose2& pose);

}  // namespace dsswarm
