#pragma once
// Which storage files a path given for a ROS 2 bag stands for, and reading
// one of them whatever its storage and rosbag2 compression.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/rosbag2/bag_metadata.hpp"
#include "io/rosbag2/storage.hpp"

namespace dsswarm::rosbag2 {

struct BagFiles {
  StorageKind storage = StorageKind::Mcap;
  std::vector<std::filesystem::path> paths;  // in recording order
  Compression compression = Compression::None;
  std::vector<std::string> warnings;  // how the files were found, when it is not the usual way
};

// By the file name: .db3 or .mcap (any case).
std::optional<StorageKind> storage_kind_of(const std::filesystem::path& file);

// `path`: a bag folder with metadata.yaml; a folder without one that holds
// exactly one .db3 or .mcap file (warning); or one such file (warning if the
// folder's metadata.yaml lists others). Throws InputError otherwise, naming
// the path ("no metadata.yaml in FOLDER ...").
BagFiles locate_bag_files(const std::filesystem::path& path);

// Reads one storage file (mcap_reader.hpp, db3_reader.hpp); with
// Compression::File the file is a zstd stream of the storage file.
std::vector<StorageTopic> read_storage_file(const std::filesystem::path& path, StorageKind storage,
                                            Compression compression, const TopicFilter& wanted,
                                            const MessageHandler& on_message);

}  // namespace dsswarm::rosbag2
