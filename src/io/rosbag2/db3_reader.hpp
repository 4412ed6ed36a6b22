#pragma once
// rosbag2's SQLite storage (.db3, the default up to Humble): table `topics`
// (id, name, type, serialization_format, ...) and table `messages` (id,
// topic_id, timestamp, data), rows in the order they were written.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "io/rosbag2/storage.hpp"

namespace dsswarm::rosbag2 {

// Opens the file read-only and hands over the wanted messages in file order
// (row id). Returns every topic, sorted by name. Throws InputError naming the
// file for a file SQLite cannot read (not a database, damaged, truncated) or
// a database without rosbag2's tables.
std::vector<StorageTopic> read_db3_file(const std::filesystem::path& path,
                                        const TopicFilter& wanted,
                                        const MessageHandler& on_message);

// The same for the bytes of a .db3 file in memory; `name` names it in errors.
std::vector<StorageTopic> read_db3_bytes(std::span<std::uint8_t> bytes, const std::string& name,
                                         const TopicFilter& wanted,
                                         const MessageHandler& on_message);

}  // namespace dsswarm::rosbag2
