#include "io/rosbag2/storage_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <optional>
#include <streambuf>

#include "common/errors.hpp"
#include "io/rosbag2/db3_reader.hpp"
#include "io/rosbag2/decompress.hpp"
#include "io/rosbag2/mcap_reader.hpp"

namespace dsswarm::rosbag2 {
namespace {

namespace fs = std::filesystem;

BagFiles from_folder_without_metadata(const fs::path& dir) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    if (entry.is_regular_file(ec) && storage_kind_of(entry.path())) found.push_back(entry.path());
  }
  std::sort(found.begin(), found.end());
  if (found.empty()) {
    throw InputError(fmt::format("no {} in {}, and no .db3 or .mcap file: not a ROS 2 bag",
                                 kMetadataFile, dir.string()));
  }
  if (found.size() > 1) {
    std::string names;
    for (const fs::path& f : found) {
      if (!names.empty()) names.append(", ");
      names.append(f.filename().string());
    }
    throw InputError(fmt::format("no {} in {}, which holds {} storage files ({}): `ros2 bag "
                                 "reindex` writes one; or pass a single file",
                                 kMetadataFile, dir.string(), found.size(), names));
  }
  return BagFiles{*storage_kind_of(found.front()), found, Compression::None,
                  {fmt::format("no {} in {}: reading its only storage file {} (`ros2 bag "
                               "reindex` writes {})",
                               kMetadataFile, dir.string(), found.front().filename().string(),
                               kMetadataFile)}};
}

// One storage file; the folder's metadata.yaml, if any, says how it is compressed.
BagFiles from_file(const fs::path& file) {
  const std::optional<StorageKind> storage = storage_kind_of(file);
  if (!storage) {
    throw InputError(file.string() + ": not a ROS 2 bag (a folder, or a .db3 or .mcap file)");
  }
  BagFiles out{*storage, {file}, Compression::None, {}};
  const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::exists(dir / kMetadataFile, ec)) return out;
  try {
    const BagMetadata metadata = read_bag_metadata(dir);
    out.compression = metadata.compression;
    if (metadata.files.size() > 1) {
      out.warnings.push_back(fmt::format("{} is one of {} storage files of the bag in {}: reading "
                                         "only this one (pass the folder to read them all)",
                                         file.string(), metadata.files.size(), dir.string()));
    }
  } catch (const InputError& e) {
    out.warnings.push_back(
        fmt::format("ignoring {}: {}", (dir / kMetadataFile).string(), e.what()));
  }
  return out;
}

// Reads a whole file of at most `max_bytes`.
std::vector<std::uint8_t> read_file(const fs::path& path, std::size_t max_bytes) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) throw InputError(path.string() + ": cannot open");
  if (size > max_bytes) {
    throw InputError(fmt::format("{}: {} bytes exceed the cap of {}", path.string(), size,
                                 max_bytes));
  }
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (in.gcount() != static_cast<std::streamsize>(bytes.size())) {
    throw InputError(path.string() + ": read error");
  }
  return bytes;
}

// An istream over bytes in memory.
class BytesBuffer : public std::streambuf {
 public:
  explicit BytesBuffer(std::vector<std::uint8_t>& bytes) {
    char* begin = reinterpret_cast<char*>(bytes.data());
    setg(begin, begin, begin + bytes.size());
  }
};

}  // namespace

std::optional<StorageKind> storage_kind_of(const fs::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".db3") return StorageKind::Sqlite3;
  if (extension == ".mcap") return StorageKind::Mcap;
  return std::nullopt;
}

BagFiles locate_bag_files(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) throw InputError(path.string() + ": no such file or directory");
  if (!fs::is_directory(status)) return from_file(path);
  if (!fs::exists(path / kMetadataFile, ec)) return from_folder_without_metadata(path);
  BagMetadata metadata = read_bag_metadata(path);
  return BagFiles{metadata.storage, std::move(metadata.files), metadata.compression, {}};
}

std::vector<StorageTopic> read_storage_file(const fs::path& path, StorageKind storage,
                                            Compression compression, const TopicFilter& wanted,
                                            const MessageHandler& on_message) {
  if (compression != Compression::File) {
    return storage == StorageKind::Mcap ? read_mcap_file(path, wanted, on_message)
                                        : read_db3_file(path, wanted, on_message);
  }
  const std::string name = path.string();
  std::vector<std::uint8_t> bytes =
      zstd_decompress(read_file(path, kMaxChunkBytes), kMaxChunkBytes, name);
  if (storage == StorageKind::Sqlite3) return read_db3_bytes(bytes, name, wanted, on_message);
  BytesBuffer buffer(bytes);
  std::istream in(&buffer);
  return read_mcap(in, bytes.size(), name, wanted, on_message);
}

}  // namespace dsswarm::rosbag2
