#pragma once
// Reading MCAP bytes safely: a record's fields with every length checked
// against the record, and the file front to back with its running CRC.
#include <cstddef>
#include <cstdint>
#include <istream>
#include <span>
#include <string>
#include <vector>

#include "io/rosbag2/mcap_format.hpp"

namespace dsswarm::mcap {

// CRC32 (IEEE 802.3, zlib's) of `bytes`, continuing the running `crc`.
std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0);

const char* op_name(Op op);

template <typename T>
T load_le(const std::uint8_t* p) {
  T v = 0;
  for (std::size_t i = sizeof(T); i-- > 0;) v = static_cast<T>((v << 8) | p[i]);
  return v;
}

// The fields of one record's content; `where` ("file: Channel record at byte
// N") starts every error (InputError).
class Fields {
 public:
  Fields(std::span<const std::uint8_t> bytes, std::string where)
      : bytes_(bytes), where_(std::move(where)) {}
  Fields(std::vector<std::uint8_t>&&, std::string) = delete;  // would dangle

  template <typename T>
  T number(const char* field) {
    return load_le<T>(take(sizeof(T), field).data());
  }
  std::string string(const char* field) {
    const auto bytes = take(number<std::uint32_t>(field), field);
    return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
  }
  // Bytes with a length prefix of type Length.
  template <typename Length>
  std::span<const std::uint8_t> bytes(const char* field) {
    return take(number<Length>(field), field);
  }
  std::span<const std::uint8_t> rest() { return take(bytes_.size() - pos_, "data"); }
  const std::string& where() const { return where_; }

 private:
  std::span<const std::uint8_t> take(std::uint64_t n, const char* field);

  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
  std::string where_;
};

// The file read front to back, with the running CRC of what was read.
// Reading past `size` is an InputError naming the file ("truncated").
class FileBytes {
 public:
  FileBytes(std::istream& in, std::uint64_t size, std::string name)
      : in_(in), size_(size), name_(std::move(name)) {}

  std::uint64_t pos() const { return pos_; }
  std::uint64_t left() const { return size_ - pos_; }
  std::uint32_t crc() const { return crc_; }
  const std::string& name() const { return name_; }

  void read(std::span<std::uint8_t> out, const std::string& what);
  // `n` must be at most left() (record lengths are checked against it).
  std::vector<std::uint8_t> read_vector(std::uint64_t n, const std::string& what);
  // Reads and hashes `n` bytes a piece at a time, keeping none.
  void skip(std::uint64_t n, const std::string& what);

 private:
  std::istream& in_;
  std::uint64_t size_;
  std::string name_;
  std::uint64_t pos_ = 0;
  std::uint32_t crc_ = 0;
};

}  // namespace dsswarm::mcap
