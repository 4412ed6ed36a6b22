#pragma once
// Live output for ROS 2 tools (rviz2, Foxglove, Nav2): the map as
// nav_msgs/OccupancyGrid on /map, and the robot's pose — tf map → odom
// (REP 105), geometry_msgs/PoseStamped on <ns>/pose, nav_msgs/Path on <ns>/path.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "geometry/pose2.hpp"
#include "grid/grid_raster.hpp"
#include "io/maps/map_server.hpp"
#include "net/dds.hpp"
#include "net/ros2_types.hpp"

namespace dsswarm::net {

using SteadyClock = std::chrono::steady_clock;

struct MapPublisherConfig {
  std::string ns;            // "" and the absolute default topic: /map
  std::string topic = "/map";
  std::string frame = "map";
  double min_period = 1.0;   // s between maps (Nav2 and rviz2 need no more than 1 Hz)
  // A write that blocks longer (a slow reader of a multi-megabyte map) is
  // given up and counted as skipped; the next map supersedes it anyway.
  std::chrono::milliseconds max_blocking{2000};
  MapServerOptions classes;  // occupied / free thresholds, as map_server reads our saved maps
};

struct MapPublisherStats {
  std::uint64_t published = 0;
  std::uint64_t skipped = 0;     // the write timed out
  std::uint64_t superseded = 0;  // replaced by a newer map before it was written
};

// Reliable + transient local, KEEP_LAST(1): Nav2 and late-joining viewers get
// the newest map. Cells are row-major from the origin (row 0 = lowest y), −1
// unknown, 0 free, 100 occupied (occupancy_grid_value). Maps are converted
// and written on a worker thread, so the caller never waits for the network.
class MapPublisher {
 public:
  MapPublisher(Participant& participant, const MapPublisherConfig& config = {});
  ~MapPublisher();  // a map not yet written is dropped; flush() first to keep it
  MapPublisher(const MapPublisher&) = delete;
  MapPublisher& operator=(const MapPublisher&) = delete;

  // True when min_period has passed since the last map was handed over.
  bool due(SteadyClock::time_point now) const;
  // Hands a map over (replacing one still waiting) and restarts the period.
  // Throws InputError for an empty or inconsistent raster.
  void publish(GridRaster raster, double stamp, SteadyClock::time_point now = SteadyClock::now());
  // The throttled form: calls make_raster() only when due. Returns whether it did.
  template <class MakeRaster>
  bool publish_if_due(SteadyClock::time_point now, double stamp, MakeRaster&& make_raster) {
    if (!due(now)) return false;
    publish(make_raster(), stamp, now);
    return true;
  }
  // Waits until every map handed over is written or given up.
  bool flush(std::chrono::milliseconds timeout);

  MapPublisherStats stats() const;
  int subscribers() const { return writer_.matched(); }

 private:
  struct Job {
    GridRaster raster;
    double stamp = 0.0;
  };
  void run();
  void write(const Job& job);

  MapPublisherConfig config_;
  Topic<ros::OccupancyGrid> topic_;
  Writer<ros::OccupancyGrid> writer_;
  std::string frame_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<Job> pending_;
  bool writing_ = false;
  bool stop_ = false;
  std::optional<SteadyClock::time_point> last_handed_;
  MapPublisherStats stats_;
  std::thread worker_;  // last: starts once everything above exists
};

// The whole OccupancyGrid message for a raster (the data points at `cells`,
// which must hold occupancy_grid_value of every cell).
ros::OccupancyGrid to_occupancy_grid(const GridRaster& raster, const std::vector<std::int8_t>& cells, double stamp,
                                     const std::string& frame);

struct PoseOutputConfig {
  std::string ns;  // the robot's ROS namespace ("/robot1"); "" = none
  std::string pose_topic = "pose";
  std::string path_topic = "path";
  std::string tf_topic = "/tf";
  std::string map_frame = "map";
  std::string odom_frame = "odom";
  std::string base_frame = "base_link";
  double path_min_step = 0.05;       // m, or 0.05 rad: closer poses are not added to the path
  std::size_t path_max_poses = 2000;  // beyond, every other pose is dropped (the path stays whole)
  double path_period = 1.0;          // s between path messages
  // Our writes never stall the caller longer than this; a blocked write is skipped.
  std::chrono::milliseconds max_blocking{20};
};

class PoseOutput {
 public:
  PoseOutput(Participant& participant, const PoseOutputConfig& config = {});
  PoseOutput(const PoseOutput&) = delete;  // messages point into config_
  PoseOutput& operator=(const PoseOutput&) = delete;

  // tf map → odom = map_pose ⊕ odom_pose⁻¹ (REP 105), or map → base_frame
  // when the robot has no odometry; the pose (frame map); the path, at most
  // every path_period. Returns false when a write was skipped (blocked).
  bool publish(double stamp, const Pose2& map_pose, const std::optional<Pose2>& odom_pose,
               SteadyClock::time_point now = SteadyClock::now());

  std::size_t path_size() const { return path_.size(); }

 private:
  void extend_path(double stamp, const Pose2& pose);

  PoseOutputConfig config_;
  Topic<ros::TFMessage> tf_topic_;
  Topic<ros::PoseStamped> pose_topic_;
  Topic<ros::Path> path_topic_;
  Writer<ros::TFMessage> tf_writer_;
  Writer<ros::PoseStamped> pose_writer_;
  Writer<ros::Path> path_writer_;
  std::vector<ros::PoseStamped> path_;  // frame_id points at config_.map_frame
  std::optional<SteadyClock::time_point> last_path_;
};

}  // namespace dsswarm::net
