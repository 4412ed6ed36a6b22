#pragma once
// Live input from a ROS 2 robot over DDS: sensor_msgs/LaserScan on <ns>/scan,
// odometry from nav_msgs/Odometry on <ns>/odom (or from /tf, odom →
// base_link), the laser mounting from /tf_static (base_link → the scan's
// frame_id, through intermediate frames). Hands out our LaserScan with the
// odometry interpolated at the scan stamp.
//
// Samples are taken as they arrive (on Cyclone's threads) into a bounded
// queue: when the consumer falls behind, the oldest scans are dropped and
// counted, never queued without bound. Every sample is checked first
// (ros2_validate.hpp); rejected ones are counted and reported in a
// rate-limited warning.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "net/dds.hpp"
#include "net/ros2_validate.hpp"
#include "sensor/laser_scan.hpp"

namespace dsswarm::net {

enum class OdometrySource {
  kTopic,  // nav_msgs/Odometry on odom_topic
  kTf,     // the odom_frame → base_frame transform on /tf
  kNone,   // scans without odometry
};

struct LiveInputConfig {
  std::string ns;  // the robot's ROS namespace ("/robot1"); "" = none
  std::string scan_topic = "scan";  // relative names go under ns
  std::string odom_topic = "odom";
  std::string tf_topic = "/tf";
  std::string tf_static_topic = "/tf_static";
  OdometrySource odometry = OdometrySource::kTopic;
  std::string odom_frame = "odom";
  // The robot frame the laser offset is relative to. With odometry from the
  // topic, the messages' child_frame_id (when set) is used instead.
  std::string base_frame = "base_link";
  std::size_t queue_capacity = 4;  // scans held for the consumer; the oldest is dropped beyond
  // Scans and odometry read as lidar drivers publish them (SensorDataQoS:
  // best effort, a sample may be lost under load), or reliably, which only
  // reliable publishers match (`dsswarm replay`, a bag played reliably).
  bool reliable = false;
  std::int32_t reliable_depth = 100;  // samples the reliable readers keep
  // Wall-clock seconds a scan waits for odometry on both sides of its stamp
  // (or at it) and for its laser offset; then it goes out with what is known
  // (odometry held up to max_extrapolation beyond the nearest pose, else
  // none; offset zero).
  double wait_for_odometry = 0.25;
  double max_extrapolation = 0.1;        // s (scan time)
  double odometry_history = 5.0;         // s (scan time) of odometry kept (more while a waiting scan needs it)
  std::size_t max_odometry_poses = 4096;  // hard cap whatever the stamps
  std::size_t max_static_frames = 256;
  SampleLimits limits;
  double warning_interval = 5.0;  // s between warnings about rejected samples
};

struct LiveInputStats {
  std::uint64_t scans_received = 0;   // valid scans taken from DDS
  std::uint64_t scans_delivered = 0;  // handed out by next()
  std::uint64_t scans_dropped = 0;    // oldest dropped: the consumer fell behind
  std::uint64_t scans_rejected = 0;   // failed check_scan
  std::uint64_t scans_without_odometry = 0;
  std::uint64_t odometry_received = 0;
  std::uint64_t odometry_rejected = 0;
  std::uint64_t transforms_rejected = 0;  // /tf and /tf_static
};

class LiveScanSource {
 public:
  // Subscribes at once (scan and odometry with sensor-data QoS, which also
  // matches reliable publishers; tf as tf2_ros listens). Throws ConfigError
  // for invalid topic names or settings.
  LiveScanSource(Participant& participant, const LiveInputConfig& config = {});
  ~LiveScanSource();
  LiveScanSource(const LiveScanSource&) = delete;
  LiveScanSource& operator=(const LiveScanSource&) = delete;

  // The oldest scan ready within `timeout` (nullopt on timeout or wake()).
  std::optional<LaserScan> next(std::chrono::milliseconds timeout);
  // Makes a waiting next() return now (from any thread, e.g. on shutdown).
  void wake();

  LiveInputStats stats() const;
  int scan_publishers() const;  // writers matched on the scan topic

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dsswarm::net
