// C++17: includes ROS headers (see rosbag_raw.cpp).
#include "io/rosbag/rosbag_test_writer.hpp"

#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>

#include <cmath>

namespace dsswarm::rosbag_raw {
namespace {

geometry_msgs::Quaternion yaw_quaternion(double yaw) {
  geometry_msgs::Quaternion q;
  q.w = std::cos(yaw / 2.0);
  q.z = std::sin(yaw / 2.0);
  return q;
}

geometry_msgs::TransformStamped transform(double stamp, const char* parent, const char* child,
                                          double x, double y, double theta) {
  geometry_msgs::TransformStamped tf;
  tf.header.stamp = ros::Time(stamp);
  tf.header.frame_id = parent;
  tf.child_frame_id = child;
  tf.transform.translation.x = x;
  tf.transform.translation.y = y;
  tf.transform.rotation = yaw_quaternion(theta);
  return tf;
}

}  // namespace

void write_test_bag(const std::string& path, const TestBagSpec& spec) {
  rosbag::Bag bag;
  bag.open(path, rosbag::bagmode::Write);
  switch (spec.compression) {
    case TestBagSpec::Compression::None:
      bag.setCompression(rosbag::compression::Uncompressed);
      break;
    case TestBagSpec::Compression::Bz2:
      bag.setCompression(rosbag::compression::BZ2);
      break;
    case TestBagSpec::Compression::Lz4:
      bag.setCompression(rosbag::compression::LZ4);
      break;
  }
  for (const TestBagMessage& m : spec.messages) {
    switch (m.kind) {
      case TestBagMessage::Kind::Scan: {
        sensor_msgs::LaserScan scan;
        scan.header.stamp = ros::Time(m.scan.stamp);
        scan.header.frame_id = kDefaultLaserFrame;
        scan.angle_min = m.scan.angle_min;
        scan.angle_increment = m.scan.angle_increment;
        scan.angle_max = m.scan.angle_min +
                         m.scan.angle_increment * static_cast<float>(m.scan.ranges.size()) -
                         m.scan.angle_increment;
        scan.range_min = m.scan.range_min;
        scan.range_max = m.scan.range_max;
        scan.ranges = m.scan.ranges;
        bag.write(spec.scan_topic, scan.header.stamp, scan);
        break;
      }
      case TestBagMessage::Kind::Odometry: {
        const ros::Time stamp(m.odom.stamp);
        if (!spec.odom_topic.empty()) {
          nav_msgs::Odometry odom;
          odom.header.stamp = stamp;
          odom.header.frame_id = kOdomFrame;
          odom.child_frame_id = kBaseFrame;
          odom.pose.pose.position.x = m.odom.x;
          odom.pose.pose.position.y = m.odom.y;
          odom.pose.pose.orientation = yaw_quaternion(m.odom.theta);
          bag.write(spec.odom_topic, stamp, odom);
        }
        if (spec.odometry_on_tf) {
          tf2_msgs::TFMessage tf;
          tf.transforms.push_back(
              transform(m.odom.stamp, kOdomFrame, kBaseFrame, m.odom.x, m.odom.y, m.odom.theta));
          bag.write("/tf", stamp, tf);
        }
        break;
      }
      case TestBagMessage::Kind::LaserOffset: {
        tf2_msgs::TFMessage tf;
        // Static transforms are stamped at the start of the recording.
        tf.transforms.push_back(
            transform(1.0, kBaseFrame, kDefaultLaserFrame, m.offset.x, m.offset.y, m.offset.theta));
        bag.write("/tf_static", ros::Time(1.0), tf);
        break;
      }
    }
  }
  bag.close();
}

}  // namespace dsswarm::rosbag_raw
