#pragma once
// Decompression of one ROS1 bag chunk for the structural check
// (bag_structure.cpp), bounded by what the chunk can hold.
// C++17-clean, no ROS includes.
#include <cstdint>
#include <string>
#include <vector>

#include "io/rosbag/bag_fields.hpp"

namespace dsswarm::rosbag_raw {

// The records of the chunk at byte `pos` of the bag `path` (its header
// `fields`, its stored bytes `data`). Nothing is allocated for a size the
// chunk cannot hold: a 9 kB bag claiming a 1 GB chunk made this check
// allocate (and clear) 1 GB (found by fuzzing). Throws InputError for a
// damaged chunk.
std::vector<char> decompress_chunk(const std::string& path, const Fields& fields,
                                   const std::string& data, std::uint64_t pos);

}  // namespace dsswarm::rosbag_raw
