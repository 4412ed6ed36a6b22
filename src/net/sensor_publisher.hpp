#pragma once
// Publishes our LaserScan as a ROS 2 robot does: sensor_msgs/LaserScan on
// <ns>/scan, its odometry as nav_msgs/Odometry on <ns>/odom and as /tf
// (odom → base_link), the laser mounting on /tf_static (base_link → laser).
// Header stamps are the scan's own timestamp. Used by `dsswarm replay` and
// by tests standing in for a robot.
#include <chrono>
#include <optional>
#include <string>

#include "net/dds.hpp"
#include "net/ros2_types.hpp"
#include "sensor/laser_scan.hpp"

namespace dsswarm::net {

struct SensorPublisherConfig {
  std::string ns;  // the robot's ROS namespace ("/robot1"); "" = none
  std::string scan_topic = "scan";
  std::string odom_topic = "odom";
  std::string tf_topic = "/tf";
  std::string tf_static_topic = "/tf_static";
  std::string odom_frame = "odom";
  std::string base_frame = "base_link";
  std::string laser_frame = "laser";
  bool publish_tf = true;  // odom → base_link on /tf (the Odometry topic is always published)
};

class SensorPublisher {
 public:
  // Reliable writers (ROS default QoS; tf as tf2_ros broadcasts), so both
  // reliable and best-effort (sensor-data) subscribers match.
  SensorPublisher(Participant& participant, const SensorPublisherConfig& config = {});

  // The scan; its odometry (when it has one) on odom and /tf; the laser offset
  // on /tf_static the first time and whenever it changes. Throws InputError for
  // a scan that does not fit the ROS message (no readings, non-finite geometry
  // or time).
  void publish(const LaserScan& scan);

  // Subscribers matched on every topic a LiveScanSource reads (scan and odometry).
  int subscribers() const;
  // `count` subscribers on scan, and on odometry too unless `odometry` is false.
  bool wait_for_subscribers(int count, std::chrono::milliseconds timeout, bool odometry = true) const;
  bool wait_for_acks(std::chrono::milliseconds timeout) const;
  // Publishes the laser offset on /tf_static and waits until every reliable
  // subscriber acknowledged it. A subscriber that reads /tf_static too (a
  // LiveScanSource does) has then discovered all our writers — /tf_static's
  // is made last — so the first scans are not lost to one-sided discovery
  // (a matched writer does not mean the reader knows it yet).
  bool latch_laser_offset(const Pose2& offset, double stamp, std::chrono::milliseconds timeout);

 private:
  void publish_laser_offset(const Pose2& offset, double stamp);

  SensorPublisherConfig config_;
  Topic<ros::LaserScan> scan_topic_;
  Topic<ros::Odometry> odom_topic_;
  Topic<ros::TFMessage> tf_topic_;
  Topic<ros::TFMessage> tf_static_topic_;
  Writer<ros::LaserScan> scan_writer_;
  Writer<ros::Odometry> odom_writer_;
  Writer<ros::TFMessage> tf_writer_;
  Writer<ros::TFMessage> tf_static_writer_;  // made last: see latch_laser_offset
  std::optional<Pose2> published_offset_;
};

// The ROS message for a scan, pointing at `scan`'s readings and `frame` (no copy).
ros::LaserScan to_ros_scan(const LaserScan& scan, const std::string& frame);

}  // namespace dsswarm::net
