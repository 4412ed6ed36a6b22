#pragma once
#include <chrono>
#include <optional>

#include "geometry/pose2.hpp"
#include "grid/grid_raster.hpp"

namespace dsswarm::agent {

// The live, ROS-facing side of a robot (net/ros2_output in a robot process).
class RobotOutputs {
 public:
  virtual ~RobotOutputs() = default;
  virtual void pose(double stamp, const Pose2& map_pose, const std::optional<Pose2>& odometry) = 0;
  virtual bool map_due(std::chrono::steady_clock::time_point now) const = 0;
  virtual void map(GridRaster raster, double stamp) = 0;
};

}  // namespace dsswarm::agent
