#include "io/logs/log_reader.hpp"

#include <algorithm>
#include <cctype>

#include "common/errors.hpp"
#include "io/rosbag2/rosbag2_reader.hpp"

// The bag reader is a separate, optional target (it needs ROS packages); this
// build knows about it only when CMake found that target.
#if defined(DSSWARM_HAVE_ROSBAG) && __has_include("io/rosbag/rosbag_reader.hpp")
#include "io/rosbag/rosbag_reader.hpp"
#define DSSWARM_LOGS_READ_BAGS 1
#endif

namespace dsswarm {
namespace {

bool is_bag(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".bag";
}

}  // namespace

SensorLog read_log(const std::filesystem::path& path, const LogReadOptions& options) {
  const BagReadOptions bag{options.scan_topic, options.odom_topic, options.use_tf_odometry, options.odom_topic_named};
  if (is_rosbag2_path(path)) return read_rosbag2(path, bag);
  if (is_bag(path)) {
#ifdef DSSWARM_LOGS_READ_BAGS
    return read_rosbag(path, bag);
#else
    throw InputError(path.string() + ": ROS bag support was not built (configure with DSSWARM_WITH_ROSBAG=ON "
                                     "and the ROS rosbag_storage packages installed)");
#endif
  }
  return read_carmen(path, options.carmen);
}

}  // namespace dsswarm
