#pragma once
// A sequential MCAP reader (mcap_format.hpp): every record from the leading
// to the closing magic, chunked or not, chunks uncompressed, zstd or lz4.
// Messages come in file order; the summary section and the indexes are
// checked for structure only (a sequential read does not need them).
//
// Hardened: every length is checked against the bytes left in its record and
// the file before anything is allocated, chunk and data section CRCs are
// verified when the file has them, and every problem is an InputError naming
// the file, the record and its byte offset.
#include <filesystem>
#include <istream>
#include <string>
#include <vector>

#include "io/rosbag2/storage.hpp"

namespace dsswarm::rosbag2 {

// Reads `size` bytes of MCAP from `in`; `name` names the file in errors.
// Returns every topic (channels merged by topic, sorted by name).
std::vector<StorageTopic> read_mcap(std::istream& in, std::uint64_t size, const std::string& name,
                                    const TopicFilter& wanted, const MessageHandler& on_message);

std::vector<StorageTopic> read_mcap_file(const std::filesystem::path& path,
                                         const TopicFilter& wanted,
                                         const MessageHandler& on_message);

}  // namespace dsswarm::rosbag2
