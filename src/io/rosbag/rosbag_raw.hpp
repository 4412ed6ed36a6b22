#pragma once
// The C++17 library that talks to rosbag_storage (whose headers do not
// compile as C++20) hands the C++20 reader the plain data of raw_bag.hpp.
// This header must stay C++17-clean and free of ROS includes.
#include <string>

#include "io/bag_common/raw_bag.hpp"

namespace dsswarm::rosbag_raw {

using bag::RawBag;
using bag::RawOdom;
using bag::RawScan;
using bag::RawStatic;
using bag::RawTopic;
using bag::kBaseFrame;
using bag::kDefaultLaserFrame;
using bag::kOdomFrame;

// Reads every message on the scan topic, the odometry (from the odometry
// topic, or from odom -> base_link transforms on /tf) and the base_link ->
// laser transform (/tf_static, else /tf), through bag::BagCollector. Does not
// judge the content beyond what decoding needs: a missing scan topic, say, is
// left to the caller, who has the topic list. Throws InputError naming `path` for a
// file that is not a readable ROS1 bag, a message that does not decode as the
// type its topic should carry, or an orientation quaternion that is zero or
// not finite.
RawBag read_raw_bag(const std::string& path, const BagReadOptions& options);

}  // namespace dsswarm::rosbag_raw
