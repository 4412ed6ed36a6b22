#include "io/bag_common/bag_log.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "io/bag_common/odometry_track.hpp"
#include "io/bag_common/time_order.hpp"

namespace dsswarm {
namespace {

using bag::RawBag;
using bag::RawOdom;
using bag::RawScan;
using bag::RawTopic;

const RawTopic* find_topic(const RawBag& bag, const std::string& name) {
  const auto it = std::find_if(bag.topics.begin(), bag.topics.end(),
                               [&](const RawTopic& t) { return t.name == name; });
  return it == bag.topics.end() ? nullptr : &*it;
}

std::string describe_topics(const RawBag& bag) {
  if (bag.topics.empty()) return "the bag has no topics";
  std::string out = "the bag has";
  for (const RawTopic& t : bag.topics) {
    out += fmt::format("{} {} ({}, {} messages)", &t == &bag.topics.front() ? "" : ",", t.name,
                       t.type, t.messages);
  }
  return out;
}

void check_scan_topic(const RawBag& bag, const std::string& file, const std::string& topic,
                      const char* type) {
  const RawTopic* found = find_topic(bag, topic);
  if (found == nullptr) {
    throw InputError(fmt::format("{}: no scan topic {}; {}", file, topic, describe_topics(bag)));
  }
  if (found->type != type) {
    throw InputError(fmt::format("{}: scan topic {} carries {}, not {}; {}", file, topic,
                                 found->type, type, describe_topics(bag)));
  }
  if (bag.scans.empty()) {
    throw InputError(fmt::format("{}: scan topic {} has no messages", file, topic));
  }
}

void check_odom_topic(const RawBag& bag, const std::string& file, const BagReadOptions& options,
                      const char* type) {
  if (options.use_tf_odometry) return;
  const RawTopic* found = find_topic(bag, options.odom_topic);
  if (found != nullptr && found->type != type) {
    throw InputError(fmt::format("{}: odometry topic {} carries {}, not {}; {}", file,
                                 options.odom_topic, found->type, type,
                                 describe_topics(bag)));
  }
}

LaserScan to_laser_scan(const RawScan& raw, std::size_t index, const std::string& file,
                        const std::string& topic) {
  const auto fail = [&](const std::string& what) {
    return InputError(fmt::format("{}: {} message #{} (stamp {:.6f}): {}", file, topic, index + 1,
                                  raw.stamp, what));
  };
  const std::pair<const char*, float> fields[] = {{"angle_min", raw.angle_min},
                                                  {"angle_increment", raw.angle_increment},
                                                  {"range_min", raw.range_min},
                                                  {"range_max", raw.range_max}};
  for (const auto& [name, value] : fields) {
    if (!std::isfinite(value)) throw fail(fmt::format("field {} is not finite ({})", name, value));
  }
  if (raw.ranges.size() > 1 && raw.angle_increment == 0.0F) {
    throw fail(fmt::format("field angle_increment is 0 for {} beams", raw.ranges.size()));
  }
  if (!(raw.range_max > raw.range_min)) {
    throw fail(fmt::format("field range_max ({}) is not above range_min ({})", raw.range_max,
                           raw.range_min));
  }
  LaserScan scan;
  scan.timestamp = raw.stamp;
  scan.angle_min = raw.angle_min;
  scan.angle_increment = raw.angle_increment;
  scan.range_min = raw.range_min;
  scan.range_max = raw.range_max;
  scan.ranges = raw.ranges;
  return scan;
}

std::vector<double> stamps_of(const auto& records) {
  std::vector<double> stamps;
  stamps.reserve(records.size());
  for (const auto& r : records) stamps.push_back(r.stamp);
  return stamps;
}

// Sets scan.odometry for every scan the odometry covers; adds the warnings.
void attach_odometry(const RawBag& bag, const std::vector<double>& scan_stamps,
                     const std::string& file, const BagReadOptions& options, SensorLog& log) {
  const std::string source =
      options.use_tf_odometry
          ? fmt::format("/tf ({} -> {})", bag::kOdomFrame, bag::kBaseFrame)
          : options.odom_topic;
  if (bag.odom.empty()) {
    // The option names are the CLI's: what a user who mistyped the topic needs to read.
    const std::string hint =
        options.use_tf_odometry ? ""
                                : fmt::format("; {} (--odom-topic names the odometry topic, --tf-odometry takes "
                                              "odometry from /tf)",
                                              describe_topics(bag));
    if (options.odom_topic_named && !options.use_tf_odometry && find_topic(bag, options.odom_topic) == nullptr)
      throw InputError(fmt::format("{}: no odometry topic {}{}", file, options.odom_topic, hint));
    log.warnings.push_back(fmt::format("{}: no odometry on {}: running without odometry{}", file, source, hint));
    return;
  }

  // Odometry records out of time order are glitches: leave them out.
  const std::vector<double> odom_stamps = stamps_of(bag.odom);
  const std::vector<bool> odom_in_order = longest_nondecreasing(odom_stamps);
  std::vector<OdometrySample> poses;
  poses.reserve(bag.odom.size());
  for (std::size_t i = 0; i < bag.odom.size(); ++i) {
    if (!odom_in_order[i]) continue;
    const RawOdom& o = bag.odom[i];
    poses.push_back({o.stamp, Pose2(o.x, o.y, o.theta)});
  }
  if (poses.size() < bag.odom.size()) {
    log.warnings.push_back(fmt::format(
        "{}: {} of {} odometry stamps on {} are out of time order (not used for interpolation)",
        file, bag.odom.size() - poses.size(), bag.odom.size(), source));
  }
  const OdometryTrack track(std::move(poses));

  // A scan whose stamp is out of order is looked up where its neighbours say it belongs.
  const std::vector<bool> scans_in_order = longest_nondecreasing(scan_stamps);
  const std::vector<double> times = lookup_times(scan_stamps, scans_in_order);
  const auto scans_moved =
      static_cast<std::size_t>(std::count(scans_in_order.begin(), scans_in_order.end(), false));
  if (scans_moved > 0) {
    log.warnings.push_back(fmt::format(
        "{}: {} scans with out-of-order stamps get their odometry at the time interpolated "
        "from their neighbours (stamps kept)",
        file, scans_moved));
  }

  std::size_t uncovered = 0;
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    log.scans[i].odometry = track.at(times[i], kBagMaxOdometryExtrapolation);
    uncovered += log.scans[i].odometry ? 0 : 1;
  }
  if (uncovered > 0) {
    log.warnings.push_back(
        fmt::format("{}: {} of {} scans lie more than {} s outside the odometry time span on {} "
                    "({:.6f} .. {:.6f}): left without odometry",
                    file, uncovered, log.scans.size(), kBagMaxOdometryExtrapolation, source,
                    track.first_stamp(), track.last_stamp()));
  }
}

}  // namespace

SensorLog sensor_log_from_bag(const RawBag& bag, const std::string& file,
                              const BagReadOptions& options, const BagMessageTypes& types) {
  check_scan_topic(bag, file, options.scan_topic, types.laser_scan);
  check_odom_topic(bag, file, options, types.odometry);

  SensorLog log;
  log.source = file;
  log.scans.reserve(bag.scans.size());
  std::size_t negative = 0;
  for (std::size_t i = 0; i < bag.scans.size(); ++i) {
    log.scans.push_back(to_laser_scan(bag.scans[i], i, file, options.scan_topic));
    const std::vector<float>& r = log.scans.back().ranges;
    negative += static_cast<std::size_t>(
        std::count_if(r.begin(), r.end(), [](float v) { return std::isfinite(v) && v < 0.0F; }));
  }
  // NaN and inf are REP 117's "no reading" and "no return": only negative ranges are odd.
  if (negative > 0) {
    log.warnings.push_back(fmt::format(
        "{}: {} range readings are negative (kept; they count as invalid beams)", file, negative));
  }

  if (bag.zero_header_stamps > 0) {
    log.warnings.push_back(fmt::format(
        "{}: {} messages have a zero header stamp; their bag record time is used instead", file,
        bag.zero_header_stamps));
  }
  const std::vector<double> scan_stamps = stamps_of(bag.scans);
  if (const std::size_t backwards = count_backward_steps(scan_stamps); backwards > 0) {
    log.warnings.push_back(
        fmt::format("{}: {} of {} scan timestamps run backwards (kept in file order)", file,
                    backwards, scan_stamps.size()));
  }

  Pose2 laser_offset;
  if (bag.laser_offset.found) {
    laser_offset = Pose2(bag.laser_offset.x, bag.laser_offset.y, bag.laser_offset.theta);
  } else {
    log.warnings.push_back(fmt::format(
        "{}: no {} -> {} transform on /tf_static or /tf: assuming the laser sits at the robot base",
        file, bag::kBaseFrame, bag.laser_frame));
  }
  for (LaserScan& scan : log.scans) scan.laser_offset = laser_offset;

  attach_odometry(bag, scan_stamps, file, options, log);
  return log;
}

}  // namespace dsswarm
