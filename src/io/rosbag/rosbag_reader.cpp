// C++20 half of the bag reader: the plain records of rosbag_raw (the C++17
// half that talks to rosbag_storage) become a SensorLog as for every bag.
#include "io/rosbag/rosbag_reader.hpp"

#include <system_error>

#include "common/errors.hpp"
#include "io/bag_common/bag_log.hpp"
#include "io/rosbag/rosbag_raw.hpp"

namespace dsswarm {

SensorLog read_rosbag(const std::filesystem::path& path, const RosbagOptions& options) {
  const std::string file = path.string();
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw InputError(file + ": no such file");
  if (std::filesystem::is_directory(status)) {
    throw InputError(file + ": is a directory, not a ROS1 .bag file");
  }
  const bag::RawBag bag = rosbag_raw::read_raw_bag(file, options);
  return sensor_log_from_bag(bag, file, options, kRos1MessageTypes);
}

}  // namespace dsswarm
