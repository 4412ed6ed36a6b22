#pragma once
// Reads a text file line by line, transparently decompressing gzip. Whether a
// file is compressed is decided by its first two bytes (1f 8b), never by its
// name: logs get renamed, and `.log.gz` files that were gunzipped in place
// keep their name more often than one would hope.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace dsswarm {

class TextLineReader {
 public:
  // Throws InputError naming the file if it is missing, a directory or unreadable.
  explicit TextLineReader(const std::filesystem::path& path);
  ~TextLineReader();
  TextLineReader(const TextLineReader&) = delete;
  TextLineReader& operator=(const TextLineReader&) = delete;

  // Fetches the next line without its line terminator (\n or \r\n). The view
  // stays valid until the next call. Returns false at the end of the file.
  // Throws InputError naming the file if a gzip stream is truncated or
  // corrupt, or if a line is absurdly long (a binary file, not a log).
  bool next(std::string_view& line);

  // 1-based number of the line last returned by next().
  std::size_t line_number() const { return line_number_; }
  bool compressed() const { return compressed_; }
  const std::string& name() const { return name_; }

 private:
  bool refill();  // appends more bytes to buffer_; false at end of input

  std::string name_;
  void* gz_ = nullptr;  // gzFile; kept opaque so callers need not include zlib.h
  bool compressed_ = false;
  bool at_end_ = false;
  std::string buffer_;
  std::size_t start_ = 0;  // first unconsumed byte in buffer_
  std::size_t line_number_ = 0;
};

}  // namespace dsswarm
