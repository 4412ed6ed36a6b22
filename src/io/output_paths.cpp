#include "io/output_paths.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>
#include <system_error>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void refuse(std::string_view option, const fs::path& path, const std::string& why) {
  throw ConfigError(fmt::format("{} {}: {}", option, path.string(), why));
}

// Creates and removes a temporary entry in the existing folder `dir`: a
// folder when the output needs folders made there, else a file. Returns the
// reason it failed ("" when it worked).
std::string probe(const fs::path& dir, bool make_folder) {
  std::string name = (dir / ".dsswarm-probe-XXXXXX").string();
  if (make_folder) {
    if (::mkdtemp(name.data()) == nullptr) return std::strerror(errno);
    ::rmdir(name.c_str());
  } else {
    const int fd = ::mkstemp(name.data());
    if (fd < 0) return std::strerror(errno);
    ::close(fd);
    ::unlink(name.c_str());
  }
  return "";
}

// `dir` must be a folder we can write in, or one we can create; errors show `shown`.
void check_folder(const fs::path& dir, std::string_view option, const fs::path& shown) {
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec))
      refuse(option, shown, dir == shown ? "exists and is not a folder" : dir.string() + " is not a folder");
    if (const std::string why = probe(dir, false); !why.empty())
      refuse(option, shown, fmt::format("cannot write in {}: {}", dir.string(), why));
    return;
  }
  // The nearest folder that exists must let us create the rest.
  fs::path parent = fs::absolute(dir, ec).parent_path();
  while (!fs::exists(parent, ec) && parent != parent.parent_path()) parent = parent.parent_path();
  if (!fs::is_directory(parent, ec)) refuse(option, shown, parent.string() + " is not a folder");
  if (const std::string why = probe(parent, true); !why.empty())
    refuse(option, shown, fmt::format("cannot create a folder in {}: {}", parent.string(), why));
}

}  // namespace

void check_output_directory(const fs::path& dir, std::string_view option) {
  check_folder(dir.empty() ? fs::path(".") : dir, option, dir);
}

void check_output_file(const fs::path& file, std::string_view option) {
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (fs::is_directory(status)) refuse(option, file, "is a folder, not a file");
  if (fs::exists(status) && !fs::is_regular_file(status)) refuse(option, file, "exists and is not a regular file");
  if (file.filename().empty()) refuse(option, file, "names a folder, not a file");
  check_folder(file.has_parent_path() ? file.parent_path() : fs::path("."), option, file);
}

}  // namespace dsswarm
