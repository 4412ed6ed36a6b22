#include "io/rosbag2/bag_metadata.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <ios>
#include <system_error>

#include "common/errors.hpp"

namespace dsswarm::rosbag2 {
namespace {

namespace fs = std::filesystem;

class MetadataFile {
 public:
  explicit MetadataFile(fs::path path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& what) const {
    throw InputError(fmt::format("{}: line {}: {}", path_.string(), node.Mark().line + 1, what));
  }
  // Fails at `map`'s entry `key`, or at `map` itself when the key is absent.
  [[noreturn]] void fail_at(const YAML::Node& map, const char* key, const std::string& what) const {
    const YAML::Node node = map[key];
    fail(node.IsDefined() ? node : map, what);
  }

  YAML::Node information() const {
    YAML::Node root;
    std::error_code ec;
    // A folder opens as a stream, and reading it then throws a stream error.
    if (!fs::is_regular_file(path_, ec)) throw InputError(path_.string() + ": not a file");
    try {
      root = YAML::LoadFile(path_.string());
    } catch (const YAML::BadFile&) {
      throw InputError(path_.string() + ": cannot read");
    } catch (const YAML::Exception& e) {
      throw InputError(fmt::format("{}: line {}: invalid YAML: {}", path_.string(),
                                   e.mark.line + 1, e.msg));
    } catch (const std::ios_base::failure& e) {
      throw InputError(fmt::format("{}: cannot read: {}", path_.string(), e.what()));
    }
    const YAML::Node info = root.IsMap() ? root["rosbag2_bagfile_information"] : YAML::Node();
    if (!info || !info.IsMap()) {
      throw InputError(path_.string() +
                       ": not a rosbag2 metadata file (no rosbag2_bagfile_information mapping)");
    }
    return info;
  }

  // The scalar `key` of `map`; `fallback` when absent, an error when absent without one.
  std::string text(const YAML::Node& map, const char* key, const char* fallback = nullptr) const {
    const YAML::Node node = map[key];
    if (!node) {
      if (fallback != nullptr) return fallback;
      fail(map, fmt::format("missing key '{}'", key));
    }
    if (!node.IsScalar()) fail(node, fmt::format("'{}' is not a single value", key));
    return node.Scalar();
  }

  std::vector<fs::path> files(const YAML::Node& info) const {
    const YAML::Node list = info["relative_file_paths"];
    if (!list) fail(info, "missing key 'relative_file_paths'");
    if (!list.IsSequence() || list.size() == 0) {
      fail(list, "'relative_file_paths' is not a list of storage files");
    }
    std::vector<fs::path> out;
    for (const YAML::Node& entry : list) {
      if (!entry.IsScalar()) fail(entry, "a relative_file_paths entry is not a file name");
      out.push_back(resolve(entry));
    }
    return out;
  }

 private:
  // Relative to the bag folder; early rosbag2 versions wrote them relative
  // to the folder's parent (with the folder name in front).
  fs::path resolve(const YAML::Node& entry) const {
    const fs::path relative(entry.Scalar());
    const fs::path dir = path_.parent_path();
    std::error_code ec;
    for (const fs::path& candidate : {dir / relative, dir.parent_path() / relative}) {
      if (fs::is_regular_file(candidate, ec)) return candidate;
    }
    fail(entry, fmt::format("lists the storage file {}, which is not in {}", relative.string(),
                            dir.string()));
  }

  fs::path path_;
};

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return s;
}

}  // namespace

BagMetadata read_bag_metadata(const fs::path& dir) {
  const MetadataFile file(dir / kMetadataFile);
  const YAML::Node info = file.information();
  BagMetadata out;
  const std::string storage = file.text(info, "storage_identifier");
  if (storage == "sqlite3") {
    out.storage = StorageKind::Sqlite3;
  } else if (storage == "mcap") {
    out.storage = StorageKind::Mcap;
  } else {
    file.fail_at(info, "storage_identifier",
                 fmt::format("storage '{}' is not supported (sqlite3 or mcap)", storage));
  }
  out.files = file.files(info);

  const std::string mode = upper(file.text(info, "compression_mode", ""));
  const std::string format = file.text(info, "compression_format", "");
  if (mode == "FILE" || mode == "MESSAGE") {
    if (format != "zstd") {
      file.fail_at(info, "compression_format",
                   fmt::format("compression format '{}' is not supported (zstd)", format));
    }
    out.compression = mode == "FILE" ? Compression::File : Compression::Message;
  } else if (!mode.empty() && mode != "NONE") {
    file.fail_at(info, "compression_mode",
                 fmt::format("compression mode '{}' is not supported (FILE, MESSAGE or none)",
                             mode));
  }
  return out;
}

}  // namespace dsswarm::rosbag2
