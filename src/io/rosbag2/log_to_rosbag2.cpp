// messages_from_log (rosbag2_test_writer.hpp): a SensorLog as the messages
// a ROS 2 robot would have recorded, such that the bag reader gives the same
// scans, stamps and odometry back.
#include "io/bag_common/time_order.hpp"
#include "io/rosbag2/rosbag2_test_writer.hpp"

namespace dsswarm::rosbag2_test {
namespace {

ros2::Time add_nanoseconds(ros2::Time t, int delta) {
  const std::int64_t ns = static_cast<std::int64_t>(t.nanosec) + delta;
  constexpr std::int64_t kNanos = 1'000'000'000;
  const std::int64_t carry = ns < 0 ? -1 : ns >= kNanos ? 1 : 0;
  return {t.sec + static_cast<std::int32_t>(carry),
          static_cast<std::uint32_t>(ns - carry * kNanos)};
}

// The latest and the earliest Time whose seconds (as the reader computes
// them) are at most and at least `t`: one Time when a Time hits t exactly.
std::pair<ros2::Time, ros2::Time> bracket(double t) {
  ros2::Time low = ros2::time_from_seconds(t);
  while (ros2::to_seconds(low) > t) low = add_nanoseconds(low, -1);
  ros2::Time high = low;
  while (ros2::to_seconds(high) < t) high = add_nanoseconds(high, 1);
  return {low, high};
}

ros2::LaserScan scan_message(const LaserScan& scan) {
  ros2::LaserScan m;
  m.header = {ros2::time_from_seconds(scan.timestamp), "laser"};
  m.angle_min = static_cast<float>(scan.angle_min);
  m.angle_increment = static_cast<float>(scan.angle_increment);
  m.angle_max = m.angle_min + m.angle_increment * static_cast<float>(scan.ranges.size() - 1);
  m.range_min = static_cast<float>(scan.range_min);
  m.range_max = static_cast<float>(scan.range_max);
  m.ranges = scan.ranges;
  return m;
}

}  // namespace

std::vector<BagMessage> messages_from_log(const SensorLog& log) {
  std::vector<BagMessage> out;
  if (log.scans.empty()) return out;
  // The reader looks each scan up at a time computed from the stamps it
  // reads: compute the same, and put the scan's odometry right there (two
  // samples with the same pose when no Time hits it: interpolating between
  // them gives that pose exactly).
  std::vector<double> stamps;
  for (const LaserScan& s : log.scans) {
    stamps.push_back(ros2::to_seconds(ros2::time_from_seconds(s.timestamp)));
  }
  const std::vector<double> times = lookup_times(stamps, longest_nondecreasing(stamps));

  const Pose2& offset = log.scans.front().laser_offset;
  out.push_back(bag_message("/tf_static", stamps.front(),
                            transform(stamps.front(), "base_link", "laser", offset.x, offset.y,
                                      offset.theta)));
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    const LaserScan& scan = log.scans[i];
    if (scan.odometry) {
      const auto [low, high] = bracket(times[i]);
      const Pose2& p = *scan.odometry;
      std::vector<ros2::Time> samples{low};
      if (!(high == low)) samples.push_back(high);
      for (const ros2::Time& t : samples) {
        const double at = ros2::to_seconds(t);
        ros2::Odometry odom = odometry(at, p.x, p.y, p.theta);
        odom.header.stamp = t;
        ros2::TFMessage tf = transform(at, "odom", "base_link", p.x, p.y, p.theta);
        tf.transforms.front().header.stamp = t;
        out.push_back(bag_message("/odom", at, odom));
        out.push_back(bag_message("/tf", at, tf));
      }
    }
    out.push_back(bag_message("/scan", scan.timestamp, scan_message(scan)));
  }
  return out;
}

}  // namespace dsswarm::rosbag2_test
