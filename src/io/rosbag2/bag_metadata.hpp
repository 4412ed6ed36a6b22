#pragma once
// The part of a rosbag2 `metadata.yaml` a reader needs: the storage plugin,
// the storage files in recording order, and how they are compressed.
//
//   rosbag2_bagfile_information:
//     version: 5
//     storage_identifier: mcap          # or sqlite3
//     relative_file_paths: [run_0.mcap, run_1.mcap]
//     compression_format: ""            # or zstd
//     compression_mode: ""              # or FILE, MESSAGE
//     topics_with_message_count: ...    # (not needed: the storage files list their topics)
#include <filesystem>
#include <string>
#include <vector>

namespace dsswarm::rosbag2 {

enum class StorageKind { Sqlite3, Mcap };
enum class Compression { None, File, Message };  // rosbag2's compression_mode (zstd only)

struct BagMetadata {
  StorageKind storage = StorageKind::Mcap;
  std::vector<std::filesystem::path> files;  // resolved, in recording order
  Compression compression = Compression::None;
};

// Reads `dir`/metadata.yaml. Throws InputError naming the file (and the line,
// where the YAML says) for invalid YAML, missing keys, an unknown storage or
// compression, and listed files that are not there.
BagMetadata read_bag_metadata(const std::filesystem::path& dir);

inline constexpr const char* kMetadataFile = "metadata.yaml";

}  // namespace dsswarm::rosbag2
