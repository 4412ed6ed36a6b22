#include "net/ros2_output.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <utility>

#include "common/errors.hpp"
#include "net/qos.hpp"
#include "net/ros_names.hpp"

namespace dsswarm::net {
namespace {

void check_raster(const GridRaster& r) {
  const bool consistent = r.width > 0 && r.height > 0 &&
                          r.cells.size() == static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height);
  if (!consistent || !std::isfinite(r.resolution) || r.resolution <= 0.0 || !r.origin.allFinite()) {
    throw InputError(fmt::format("cannot publish a map of {}x{} cells ({} given), resolution {}", r.width, r.height,
                                 r.cells.size(), r.resolution));
  }
}

const MapPublisherConfig& checked(const MapPublisherConfig& c) {
  check_map_server_options(c.classes);
  if (!(std::isfinite(c.min_period) && c.min_period >= 0.0)) {
    throw ConfigError(fmt::format("map output: min_period {} is not >= 0", c.min_period));
  }
  return c;
}

bool moved_by(const Pose2& a, const Pose2& b, double step) {
  return std::hypot(b.x - a.x, b.y - a.y) >= step || std::abs(normalize_angle(b.theta - a.theta)) >= step;
}

}  // namespace

ros::OccupancyGrid to_occupancy_grid(const GridRaster& raster, const std::vector<std::int8_t>& cells, double stamp,
                                     const std::string& frame) {
  ros::OccupancyGrid msg{};
  msg.header.stamp = to_ros_time(stamp);
  msg.header.frame_id = borrow(frame);
  msg.info.map_load_time = msg.header.stamp;
  msg.info.resolution = static_cast<float>(raster.resolution);
  msg.info.width = static_cast<std::uint32_t>(raster.width);
  msg.info.height = static_cast<std::uint32_t>(raster.height);
  // The origin is the corner of cell (0, 0), as in map_server's YAML.
  msg.info.origin = to_ros_pose({raster.origin.x(), raster.origin.y(), 0.0});
  borrow(msg.data, cells);
  return msg;
}

// ---------------------------------------------------------------- MapPublisher

MapPublisher::MapPublisher(Participant& participant, const MapPublisherConfig& config)
    : config_(checked(config)),
      topic_(participant, ros_topic_name(config.ns, config.topic)),
      writer_(topic_, ros_transient_local(1).reliable(config.max_blocking)),
      frame_(config.frame),
      worker_([this] { run(); }) {}

MapPublisher::~MapPublisher() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  worker_.join();
}

bool MapPublisher::due(SteadyClock::time_point now) const {
  const std::lock_guard lock(mutex_);
  return !last_handed_ || std::chrono::duration<double>(now - *last_handed_).count() >= config_.min_period;
}

void MapPublisher::publish(GridRaster raster, double stamp, SteadyClock::time_point now) {
  check_raster(raster);
  {
    const std::lock_guard lock(mutex_);
    if (pending_) ++stats_.superseded;
    pending_ = Job{std::move(raster), stamp};
    last_handed_ = now;
  }
  changed_.notify_all();
}

bool MapPublisher::flush(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  return changed_.wait_for(lock, timeout, [this] { return !pending_ && !writing_; });
}

MapPublisherStats MapPublisher::stats() const {
  const std::lock_guard lock(mutex_);
  return stats_;
}

void MapPublisher::run() {
  std::unique_lock lock(mutex_);
  while (true) {
    changed_.wait(lock, [this] { return stop_ || pending_.has_value(); });
    if (stop_) return;
    const Job job = std::move(*pending_);
    pending_.reset();
    writing_ = true;
    lock.unlock();
    write(job);
    lock.lock();
    writing_ = false;
    changed_.notify_all();
  }
}

void MapPublisher::write(const Job& job) {
  std::vector<std::int8_t> cells(job.raster.cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) cells[i] = occupancy_grid_value(job.raster.cells[i], config_.classes);
  bool written = false;
  try {
    written = writer_.try_write(to_occupancy_grid(job.raster, cells, job.stamp, frame_));
  } catch (const std::exception& e) {  // a worker thread: report, count, carry on
    spdlog::error("/map: {}", e.what());
  }
  const std::lock_guard lock(mutex_);
  ++(written ? stats_.published : stats_.skipped);
}

// ---------------------------------------------------------------- PoseOutput

PoseOutput::PoseOutput(Participant& participant, const PoseOutputConfig& config)
    : config_(config),
      tf_topic_(participant, ros_topic_name(config.ns, config.tf_topic)),
      pose_topic_(participant, ros_topic_name(config.ns, config.pose_topic)),
      path_topic_(participant, ros_topic_name(config.ns, config.path_topic)),
      tf_writer_(tf_topic_, ros_tf().reliable(config.max_blocking)),
      pose_writer_(pose_topic_, ros_default(10).reliable(config.max_blocking)),
      path_writer_(path_topic_, ros_default(1).reliable(config.max_blocking)) {
  if (config_.path_max_poses < 2) throw ConfigError("pose output: path_max_poses must be >= 2");
}

bool PoseOutput::publish(double stamp, const Pose2& map_pose, const std::optional<Pose2>& odom_pose,
                         SteadyClock::time_point now) {
  // REP 105: map → odom makes map → odom → base_link end at the map pose.
  const Pose2 map_from_child = odom_pose ? map_pose * odom_pose->inverse() : map_pose;
  const std::string& child = odom_pose ? config_.odom_frame : config_.base_frame;
  ros::TransformStamped t = to_ros_transform_stamped(stamp, config_.map_frame, child, map_from_child);
  ros::TFMessage tf{};
  tf.transforms = {1, 1, &t, false};
  bool all_written = tf_writer_.try_write(tf);

  ros::PoseStamped pose{};
  pose.header.stamp = t.header.stamp;
  pose.header.frame_id = borrow(config_.map_frame);
  pose.pose = to_ros_pose(map_pose);
  all_written = pose_writer_.try_write(pose) && all_written;

  extend_path(stamp, map_pose);
  if (!last_path_ || std::chrono::duration<double>(now - *last_path_).count() >= config_.path_period) {
    ros::Path path{};
    path.header = pose.header;
    borrow(path.poses, path_);
    all_written = path_writer_.try_write(path) && all_written;
    last_path_ = now;
  }
  return all_written;
}

void PoseOutput::extend_path(double stamp, const Pose2& pose) {
  if (!path_.empty() && !moved_by(to_pose2(path_.back().pose), pose, config_.path_min_step)) return;
  ros::PoseStamped p{};
  p.header.stamp = to_ros_time(stamp);
  p.header.frame_id = borrow(config_.map_frame);
  p.pose = to_ros_pose(pose);
  path_.push_back(p);
  if (path_.size() <= config_.path_max_poses) return;
  // Halve the resolution rather than forget the start: the path stays whole.
  std::vector<ros::PoseStamped> kept;
  for (std::size_t i = 0; i < path_.size(); i += 2) kept.push_back(path_[i]);
  if (path_.size() % 2 == 0) kept.push_back(path_.back());
  path_ = std::move(kept);
}

}  // namespace dsswarm::net
