#include "io/logs/text_line_reader.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

constexpr std::size_t kChunkBytes = 256 * 1024;
// A CARMEN line holds a few thousand numbers at most; a "line" this long means
// the file is not text, and reading on would only eat memory.
constexpr std::size_t kMaxLineBytes = 64 * 1024 * 1024;

gzFile as_gz(void* p) { return static_cast<gzFile>(p); }

bool starts_with_gzip_magic(const std::filesystem::path& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    throw InputError(fmt::format("{}: cannot open: {}", path.string(), std::strerror(errno)));
  }
  unsigned char magic[2] = {0, 0};
  const std::size_t got = std::fread(magic, 1, 2, f);
  std::fclose(f);
  return got == 2 && magic[0] == 0x1f && magic[1] == 0x8b;
}

}  // namespace

TextLineReader::TextLineReader(const std::filesystem::path& path) : name_(path.string()) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw InputError(name_ + ": no such file");
  if (std::filesystem::is_directory(status)) throw InputError(name_ + ": is a directory, not a log file");
  compressed_ = starts_with_gzip_magic(path);
  // zlib reads uncompressed files verbatim ("transparent" mode), so one code
  // path serves both; compressed_ only decides which errors can occur.
  gz_ = gzopen(path.c_str(), "rb");
  if (gz_ == nullptr) {
    throw InputError(fmt::format("{}: cannot open: {}", name_, errno != 0 ? std::strerror(errno) : "out of memory"));
  }
  gzbuffer(as_gz(gz_), kChunkBytes);
}

TextLineReader::~TextLineReader() {
  if (gz_ != nullptr) gzclose(as_gz(gz_));
}

bool TextLineReader::refill() {
  if (at_end_) return false;
  const std::size_t old_size = buffer_.size();
  buffer_.resize(old_size + kChunkBytes);
  const int got = gzread(as_gz(gz_), buffer_.data() + old_size, static_cast<unsigned>(kChunkBytes));
  int errnum = Z_OK;
  const char* message = gzerror(as_gz(gz_), &errnum);
  if (got < 0 || (errnum != Z_OK && errnum != Z_BUF_ERROR)) {
    buffer_.resize(old_size);
    if (errnum == Z_ERRNO) throw InputError(fmt::format("{}: read error: {}", name_, std::strerror(errno)));
    // zlib prefixes its message with the path; keep only the reason.
    std::string_view reason = message;
    if (reason.substr(0, name_.size() + 2) == name_ + ": ") reason.remove_prefix(name_.size() + 2);
    throw InputError(fmt::format("{}: corrupt gzip data{} ({})", name_,
                                 line_number_ > 0 ? fmt::format(" after line {}", line_number_) : "", reason));
  }
  buffer_.resize(old_size + static_cast<std::size_t>(got));
  if (got == 0) {
    at_end_ = true;
    // zlib reports a stream that stops before its end marker only as
    // Z_BUF_ERROR at the end of input; without this check a truncated
    // download would silently read as a shorter log.
    if (errnum == Z_BUF_ERROR) {
      throw InputError(fmt::format("{}: gzip data is truncated (file ends after line {}); "
                                   "the file is incomplete",
                                   name_, line_number_));
    }
    return false;
  }
  return true;
}

bool TextLineReader::next(std::string_view& line) {
  std::size_t searched = start_;
  for (;;) {
    const std::size_t newline = buffer_.find('\n', searched);
    if (newline != std::string::npos) {
      std::size_t end = newline;
      if (end > start_ && buffer_[end - 1] == '\r') --end;
      line = std::string_view(buffer_).substr(start_, end - start_);
      start_ = newline + 1;
      ++line_number_;
      return true;
    }
    // No complete line buffered: drop consumed bytes, then read more.
    buffer_.erase(0, start_);
    start_ = 0;
    searched = buffer_.size();
    if (buffer_.size() > kMaxLineBytes) {
      throw InputError(fmt::format("{}:{}: line longer than {} MB; this is not a text log", name_,
                                   line_number_ + 1, kMaxLineBytes / (1024 * 1024)));
    }
    if (!refill()) {
      if (buffer_.empty()) return false;
      // Last line without a terminating newline.
      std::size_t end = buffer_.size();
      if (buffer_[end - 1] == '\r') --end;
      line = std::string_view(buffer_).substr(0, end);
      start_ = buffer_.size();
      ++line_number_;
      return true;
    }
  }
}

}  // namespace dsswarm
