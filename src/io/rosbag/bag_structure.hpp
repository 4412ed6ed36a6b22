#pragma once
// A structural check of ROS1 bag files (format 2.0) before rosbag_storage
// opens them. rosbag_storage trusts every length and offset in the file: on a
// damaged bag it reads past its buffers (a crash, found by fuzzing) or
// allocates gigabytes. This walks every record, decompresses every chunk and
// checks that lengths, chunk sizes, index offsets and connection ids agree,
// so rosbag_storage only ever sees a file it can read safely.
// C++17-clean, no ROS includes.
#include <istream>
#include <string>

namespace dsswarm::rosbag_raw {

// Throws InputError naming `path` (and the byte offset of the offending
// record) for a file that is not a ROS1 bag, is truncated, was not closed
// (no index), or whose records do not hang together. Bags of other format
// versions (1.2) are refused too: rosbag_storage would read them unchecked.
void check_bag_structure(const std::string& path);

// The same for a bag held in `in` (a binary stream); `name` stands for the
// path in errors.
void check_bag_structure(std::istream& in, const std::string& name);

}  // namespace dsswarm::rosbag_raw
