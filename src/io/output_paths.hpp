#pragma once
// Output locations are checked before a command starts working, so a typo in
// `--out` costs a second, not the whole run. The checks create nothing: they
// probe the folder that would hold the output with a temporary entry.
#include <filesystem>
#include <string_view>

namespace dsswarm {

// ConfigError naming `option` and `dir` unless `dir` is a folder that can be
// written into, or does not exist and can be created: an existing file, a
// parent that is a file, or a place where nothing can be created (read-only,
// /proc, no permission) is refused.
void check_output_directory(const std::filesystem::path& dir, std::string_view option);

// ConfigError naming `option` and `file` unless `file` can be written: an
// existing folder, device or other non-regular file is refused, and its folder
// must pass check_output_directory.
void check_output_file(const std::filesystem::path& file, std::string_view option);

}  // namespace dsswarm
