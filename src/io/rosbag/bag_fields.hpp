#pragma once
// The low-level pieces of ROS1 bag records (format 2.0) that the structural
// check (bag_structure.cpp) and its chunk decompression (bag_chunk.cpp) share:
// little-endian integers, header field lists and the error for a damaged
// record. C++17-clean, no ROS includes.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

namespace dsswarm::rosbag_raw {

using Fields = std::map<std::string, std::string>;

std::uint32_t le32(const char* p);
std::uint64_t le64(const char* p);

// The fields of a record header (or of a connection record's data), or false
// when the bytes are not a well-formed field list.
bool parse_fields(const char* p, std::size_t n, Fields& fields);

// For error messages: control and non-ASCII bytes as '?'.
std::string printable(std::string text);

// Throws InputError: `path` is a damaged bag, `what` being wrong with the
// record at byte `pos`.
[[noreturn]] void damaged_record(const std::string& path, const std::string& what,
                                 std::uint64_t pos);

// A fixed-size integer field (rosbag_storage insists on the exact size).
std::uint64_t fixed_size_field(const std::string& path, const Fields& fields, const char* name,
                               std::size_t size, std::uint64_t pos);

}  // namespace dsswarm::rosbag_raw
