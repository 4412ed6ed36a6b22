#include "io/atomic_file.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;

fs::path temporary_for(const fs::path& path) { return path.string() + ".tmp." + std::to_string(::getpid()); }

void require_folder(const fs::path& path) {
  if (path.has_parent_path() && !fs::is_directory(path.parent_path())) {
    throw InputError("cannot write " + path.string() + ": directory " + path.parent_path().string() +
                     " does not exist");
  }
}

// Writes the temporary sibling of `path`; removes it and throws on failure.
void write_temporary(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  const fs::path tmp = temporary_for(path);
  try {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError("cannot write " + path.string() + ": " + std::strerror(errno));
    write(out);
    out.flush();
    if (!out) throw InputError("error while writing " + path.string() + ": " + std::strerror(errno));
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

void rename_into_place(const fs::path& path) {
  std::error_code ec;
  fs::rename(temporary_for(path), path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary_for(path), ignored);
    throw InputError("cannot write " + path.string() + ": " + ec.message());
  }
}

}  // namespace

void write_file_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  require_folder(path);
  write_temporary(path, write);
  rename_into_place(path);
}

void write_file_atomically(const fs::path& path, std::string_view contents) {
  write_file_atomically(path, [&](std::ostream& out) { out.write(contents.data(), static_cast<std::streamsize>(contents.size())); });
}

void OutputFiles::add(fs::path path, std::string contents) {
  const auto same = std::find_if(files_.begin(), files_.end(), [&](const File& f) { return f.path == path; });
  if (same != files_.end()) {
    same->contents = std::move(contents);
  } else {
    files_.push_back({std::move(path), std::move(contents)});
  }
}

void OutputFiles::write_all() const {
  // Every temporary first, then the renames: a write that fails replaces nothing.
  const auto discard = [&](std::size_t from, std::size_t to) {
    for (std::size_t i = from; i < to; ++i) {
      std::error_code ignored;
      fs::remove(temporary_for(files_[i].path), ignored);
    }
  };
  std::size_t written = 0;
  try {
    for (; written < files_.size(); ++written) {
      const File& f = files_[written];
      std::error_code ec;
      if (f.path.has_parent_path()) fs::create_directories(f.path.parent_path(), ec);
      if (ec) throw InputError("cannot create folder " + f.path.parent_path().string() + ": " + ec.message());
      write_temporary(f.path, [&](std::ostream& out) {
        out.write(f.contents.data(), static_cast<std::streamsize>(f.contents.size()));
      });
    }
  } catch (...) {
    discard(0, written);
    throw;
  }
  for (std::size_t i = 0; i < files_.size(); ++i) {
    try {
      rename_into_place(files_[i].path);
    } catch (...) {
      discard(i + 1, files_.size());
      throw;
    }
  }
}

}  // namespace dsswarm
