#pragma once
// Every output file is written to a temporary sibling and renamed into place,
// so a crash or an error never leaves a half-written file, and a file that was
// already there stays intact until its replacement is complete.
#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace dsswarm {

// Calls `write` with a stream to a temporary file next to `path`, then renames
// it over `path`. If `write` throws or the stream fails, the temporary file is
// removed, `path` is untouched, and the error propagates (as InputError for
// stream failures, naming the file).
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

}  // namespace dsswarm
