#pragma once
// Every output file is written to a temporary sibling and renamed into place,
// so a crash or an error never leaves a half-written file, and a file that was
// already there stays intact until its replacement is complete. Errors name
// the file asked for, never the temporary.
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace dsswarm {

// Calls `write` with a stream to a temporary file next to `path`, then renames
// it over `path`. If `write` throws or the stream fails, the temporary file is
// removed, `path` is untouched, and the error propagates (as InputError for
// stream failures, naming the file).
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// The outputs of one command, collected in memory while it works and written
// together at the end: all of them, or (on an error) none.
class OutputFiles {
 public:
  struct File {
    std::filesystem::path path;
    std::string contents;
  };

  // A second file with the same path replaces the first.
  void add(std::filesystem::path path, std::string contents);

  // Creates the folders, writes every file to its temporary sibling, then
  // renames them into place in the order they were added. When a write fails
  // the temporaries are removed and no file is replaced (InputError naming
  // the file).
  void write_all() const;

  const std::vector<File>& files() const { return files_; }

 private:
  std::vector<File> files_;
};

}  // namespace dsswarm
