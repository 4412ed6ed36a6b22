#include "io/rosbag2/rosbag2_reader.hpp"

#include <gtest/gtest.h>

#include "apps/swarm_scenario.hpp"
#include "io/logs/log_reader.hpp"
#include "io/rosbag2/rosbag2_test_util.hpp"

namespace dsswarm::rosbag2_test {
namespace {

void expect_pose_near(const std::optional<Pose2>& actual, const Pose2& expected, double tol) {
  ASSERT_TRUE(actual.has_value());
  EXPECT_NEAR(actual->x, expected.x, tol);
  EXPECT_NEAR(actual->y, expected.y, tol);
  EXPECT_NEAR(normalize_angle(actual->theta - expected.theta), 0.0, tol);
}

// The same expectations as the ROS1 reader's test of the same recording.
void expect_small_recording(const SensorLog& log) {
  ASSERT_EQ(log.scans.size(), 5U);
  const std::vector<double> stamps{10.2, 10.4, 10.9, 10.6, 11.5};  // file order
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    EXPECT_NEAR(log.scans[i].timestamp, stamps[i], 1e-9) << i;
  }
  const LaserScan& third = log.scans[2];
  EXPECT_EQ(third.ranges, (std::vector<float>{4.0F, 40.0F, 0.0F}));
  EXPECT_EQ(third.angle_min, static_cast<float>(-kPi / 2));
  EXPECT_EQ(third.angle_increment, static_cast<float>(kPi / 2));
  EXPECT_EQ(third.range_min, 0.1F);
  EXPECT_EQ(third.range_max, 30.0F);
  for (const LaserScan& s : log.scans) {
    EXPECT_NEAR(s.laser_offset.x, 0.25, 1e-12);
    EXPECT_NEAR(s.laser_offset.y, -0.1, 1e-12);
    EXPECT_NEAR(s.laser_offset.theta, 0.05, 1e-12);
  }
  expect_pose_near(log.scans[0].odometry, Pose2(0.2, 0.4, 0.2 * kPi / 2), 1e-9);
  expect_pose_near(log.scans[1].odometry, Pose2(0.4, 0.8, 0.4 * kPi / 2), 1e-9);
  // Stamped 10.9 s between 10.4 and 10.6 in the file: looked up at 10.5 s.
  expect_pose_near(log.scans[2].odometry, Pose2(0.5, 1.0, 0.5 * kPi / 2), 1e-9);
  expect_pose_near(log.scans[3].odometry, Pose2(0.6, 1.2, 0.6 * kPi / 2), 1e-9);
  // Between 11 s and 12 s, not via the glitch at 13.5 s.
  expect_pose_near(log.scans[4].odometry, Pose2(1.0, 3.0, 0.75 * kPi), 1e-9);
  EXPECT_TRUE(has_warning(log, "1 of 5 scan timestamps run backwards")) << joined(log.warnings);
  EXPECT_TRUE(has_warning(log, "1 of 4 odometry stamps on /odom are out of time order"))
      << joined(log.warnings);
  EXPECT_TRUE(has_warning(log, "1 scans with out-of-order stamps")) << joined(log.warnings);
  EXPECT_EQ(log.warnings.size(), 3U) << joined(log.warnings);
}

TEST(Rosbag2Reader, EveryStorageFormatReadsTheSameRecording) {
  for (const Format format : kAllFormats) {
    SCOPED_TRACE(format_name(format));
    WriteOptions options;
    options.format = format;
    options.chunk_bytes = 200;  // a few messages per chunk
    const fs::path dir = write_test_bag(format_name(format), small_recording(), options);
    const SensorLog log = read_rosbag2(dir);
    EXPECT_EQ(log.source, dir.string());
    expect_small_recording(log);
  }
}

TEST(Rosbag2Reader, SplitAndCompressedBagsReadTheSame) {
  for (const Format format : {Format::Db3, Format::McapZstd}) {
    for (const auto compression : {rosbag2::Compression::None, rosbag2::Compression::File,
                                   rosbag2::Compression::Message}) {
      SCOPED_TRACE(std::string(format_name(format)) + " compression " +
                   std::to_string(static_cast<int>(compression)));
      WriteOptions options;
      options.format = format;
      options.files = 3;  // messages in file order across three storage files
      options.compression = compression;
      const fs::path dir = write_test_bag("split", small_recording(), options);
      expect_small_recording(read_rosbag2(dir));
    }
  }
}

TEST(Rosbag2Reader, OdometryFromTfWhenAsked) {
  const fs::path dir = write_test_bag("tf_only", small_recording(false), {});
  const SensorLog without = read_rosbag2(dir);
  ASSERT_EQ(without.scans.size(), 5U);
  for (const LaserScan& s : without.scans) EXPECT_FALSE(s.odometry.has_value());
  EXPECT_TRUE(has_warning(without, "no odometry on /odom: running without odometry; the bag has"))
      << joined(without.warnings);
  EXPECT_TRUE(has_warning(without, "--tf-odometry takes odometry from /tf")) << joined(without.warnings);

  BagReadOptions options;
  options.use_tf_odometry = true;
  const SensorLog with = read_rosbag2(dir, options);
  expect_pose_near(with.scans[2].odometry, Pose2(0.5, 1.0, 0.5 * kPi / 2), 1e-9);
  expect_pose_near(with.scans[4].odometry, Pose2(1.0, 3.0, 0.75 * kPi), 1e-9);
  EXPECT_TRUE(has_warning(with, "odometry stamps on /tf (odom -> base_link) are out of time order"))
      << joined(with.warnings);
}

TEST(Rosbag2Reader, TheStorageFileItselfCanBeGiven) {
  for (const Format format : {Format::Db3, Format::McapLz4}) {
    WriteOptions options;
    options.format = format;
    const fs::path dir = write_test_bag("direct", small_recording(), options);
    const fs::path file = write_bag(dir, small_recording(), options).front();
    expect_small_recording(read_rosbag2(file));

    options.files = 2;  // one of two: read alone, with a warning
    const fs::path first = write_bag(dir, small_recording(), options).front();
    const SensorLog part = read_rosbag2(first);
    EXPECT_TRUE(has_warning(part, "is one of 2 storage files of the bag in"))
        << joined(part.warnings);
    EXPECT_LT(part.scans.size(), 5U);
  }
}

TEST(Rosbag2Reader, AFolderWithoutMetadataYaml) {
  WriteOptions options;
  options.metadata = false;
  // One storage file: read, with a warning saying so.
  const fs::path dir = write_test_bag("no_metadata", small_recording(), options);
  const SensorLog log = read_rosbag2(dir);
  EXPECT_EQ(log.scans.size(), 5U);
  EXPECT_TRUE(has_warning(log, "no metadata.yaml in " + dir.string() +
                                   ": reading its only storage file no_metadata_0.mcap"))
      << joined(log.warnings);
  // Several, or none: an error naming the folder.
  options.files = 2;
  write_bag(dir, small_recording(), options);
  std::string message = input_error_of(dir);
  EXPECT_NE(message.find("no metadata.yaml in " + dir.string() + ", which holds 2 storage files"),
            std::string::npos)
      << message;
  const fs::path empty = test::fresh_dir("rosbag2/empty_folder");
  message = input_error_of(empty);
  EXPECT_NE(message.find("no metadata.yaml in " + empty.string()), std::string::npos) << message;
  EXPECT_NE(message.find("not a ROS 2 bag"), std::string::npos) << message;
}

TEST(Rosbag2Reader, WrongTopicsNameTheTopicItsTypeAndListTheBag) {
  for (const Format format : {Format::Db3, Format::McapZstd}) {
    SCOPED_TRACE(format_name(format));
    WriteOptions write;
    write.format = format;
    const fs::path dir = write_test_bag("topics", small_recording(), write);
    BagReadOptions options;
    options.scan_topic = "/odom";
    std::string message = input_error_of(dir, options);
    EXPECT_NE(message.find(dir.string() + ": scan topic /odom carries nav_msgs/msg/Odometry, not "
                                          "sensor_msgs/msg/LaserScan"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("/scan (sensor_msgs/msg/LaserScan, 5 messages)"), std::string::npos)
        << message;
    EXPECT_NE(message.find("/tf_static (tf2_msgs/msg/TFMessage, 1 messages)"), std::string::npos)
        << message;

    options.scan_topic = "/base_scan";
    message = input_error_of(dir, options);
    EXPECT_NE(message.find("no scan topic /base_scan"), std::string::npos) << message;
    EXPECT_NE(message.find("/odom (nav_msgs/msg/Odometry, 4 messages)"), std::string::npos)
        << message;

    options = {};
    options.odom_topic = "/scan";
    message = input_error_of(dir, options);
    EXPECT_NE(message.find("odometry topic /scan carries sensor_msgs/msg/LaserScan, not "
                           "nav_msgs/msg/Odometry"),
              std::string::npos)
        << message;
  }
}

TEST(Rosbag2Reader, DamagedMessagesNameFileTopicTimeAndField) {
  std::vector<BagMessage> messages = small_recording();
  for (BagMessage& m : messages) {
    if (m.topic == "/scan") {
      m.cdr.resize(m.cdr.size() - 6);  // the last ranges are cut off
      break;
    }
  }
  for (const Format format : {Format::Db3, Format::McapUnchunked}) {
    WriteOptions options;
    options.format = format;
    const fs::path dir = write_test_bag("damaged_message", messages, options);
    const std::string message = input_error_of(dir);
    EXPECT_NE(message.find("damaged_message_0."), std::string::npos) << message;
    EXPECT_NE(message.find("/scan message at t=10.200000"), std::string::npos) << message;
    EXPECT_NE(message.find("sensor_msgs/msg/LaserScan: field ranges"), std::string::npos)
        << message;
  }
}

TEST(Rosbag2Reader, NonFiniteScanGeometryAndPosesAreInputErrors) {
  std::vector<BagMessage> messages = small_recording();
  ros2::LaserScan bad = laser_scan(10.3, {1.0F});
  bad.angle_increment = std::numeric_limits<float>::quiet_NaN();
  messages.push_back(bag_message("/scan", 10.3, bad));
  std::string message = input_error_of(write_test_bag("nan_scan", messages, {}));
  EXPECT_NE(message.find("/scan message #6"), std::string::npos) << message;
  EXPECT_NE(message.find("angle_increment"), std::string::npos) << message;

  messages = small_recording();
  messages.push_back(bag_message("/odom", 11.2, odometry(11.2, std::nan(""), 0.0, 0.0)));
  message = input_error_of(write_test_bag("nan_odom", messages, {}));
  EXPECT_NE(message.find("/odom message at t=11.200000: position is not finite"),
            std::string::npos)
      << message;
}

TEST(Rosbag2Reader, ReadLogRecognisesRos2Bags) {
  const fs::path dir = write_test_bag("read_log", small_recording(), {});
  LogReadOptions options;
  options.use_tf_odometry = true;
  const SensorLog from_folder = read_log(dir, options);
  expect_pose_near(from_folder.scans[2].odometry, Pose2(0.5, 1.0, 0.5 * kPi / 2), 1e-9);
  EXPECT_EQ(read_log(dir / "read_log_0.mcap").scans.size(), 5U);
  WriteOptions db3;
  db3.format = Format::Db3;
  write_bag(dir, small_recording(), db3);
  EXPECT_EQ(read_log(dir / "read_log_0.db3").scans.size(), 5U);
  // A folder is never a CARMEN log: the error says what a ROS 2 bag folder needs.
  const fs::path empty = test::fresh_dir("rosbag2/read_log_empty");
  try {
    read_log(empty);
    ADD_FAILURE() << "an empty folder was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no metadata.yaml in"), std::string::npos) << e.what();
  }
}

TEST(Rosbag2Reader, SwarmScenarioAgentsPlayBagFolders) {
  const fs::path dir = write_test_bag("scenario/bag", small_recording(), {});
  const fs::path yaml = test::write_text(dir.parent_path() / "scenario.yaml",
                                         "agents:\n  - name: a\n    log: bag\n");
  const SwarmScenario scenario = load_swarm_scenario(yaml);
  ASSERT_EQ(scenario.streams.size(), 1U);
  EXPECT_EQ(scenario.streams[0].scans.size(), 5U);
}

TEST(Rosbag2Reader, MetadataYamlProblemsNameTheFileAndLine) {
  const fs::path dir = write_test_bag("bad_metadata", small_recording(), {});
  const fs::path yaml = dir / "metadata.yaml";
  const std::string good = read_file_bytes(yaml);
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    text.replace(text.find(from), from.size(), to);
    write_file_bytes(yaml, text);
    return input_error_of(dir);
  };
  std::string message = with("storage_identifier: mcap", "storage_identifier: leveldb");
  EXPECT_NE(message.find(yaml.string() + ": line 3: storage 'leveldb' is not supported"),
            std::string::npos)
      << message;
  message = with("    - bad_metadata_0.mcap", "    - missing.mcap");
  EXPECT_NE(message.find("lists the storage file missing.mcap, which is not in"),
            std::string::npos)
      << message;
  message = with("rosbag2_bagfile_information:", "rosbag2_bagfile_information: [");
  EXPECT_NE(message.find("invalid YAML"), std::string::npos) << message;
  message = with("compression_mode: \"\"", "compression_mode: FILE");
  EXPECT_NE(message.find("compression format '' is not supported"), std::string::npos) << message;
  write_file_bytes(yaml, "just: text\n");
  message = input_error_of(dir);
  EXPECT_NE(message.find("not a rosbag2 metadata file"), std::string::npos) << message;
  // A folder named metadata.yaml (found by the scenario fuzzer): an input
  // error, not the stream error a folder gives when read.
  fs::remove(yaml);
  fs::create_directory(yaml);
  message = input_error_of(dir);
  EXPECT_NE(message.find(yaml.string() + ": not a file"), std::string::npos) << message;
}

}  // namespace
}  // namespace dsswarm::rosbag2_test
