#pragma once
// Little-endian byte writer and bounds-checked reader for the project's own
// binary formats (.dsmap, swarm messages), whatever the host's byte order.
#include <bit>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/errors.hpp"

namespace dsswarm {

// Little-endian byte writer, whatever the host's byte order.
class ByteWriter {
 public:
  void u8(std::uint8_t v) { bytes_.push_back(v); }
  void u16(std::uint16_t v) { le(v, 2); }
  void u32(std::uint32_t v) { le(v, 4); }
  void u64(std::uint64_t v) { le(v, 8); }
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
  }
  void reserve(std::size_t n) { bytes_.reserve(n); }
  std::vector<std::uint8_t>& bytes() { return bytes_; }

 private:
  void le(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) bytes_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  std::vector<std::uint8_t> bytes_;
};

// Bounds-checked little-endian reader: every read past the end is an
// InputError saying what was being read.
class ByteReader {
 public:
  ByteReader(std::span<const std::uint8_t> bytes, std::string name, std::string what)
      : bytes_(bytes), name_(std::move(name)), what_(std::move(what)) {}

  std::size_t remaining() const { return bytes_.size() - pos_; }
  std::size_t position() const { return pos_; }

  std::span<const std::uint8_t> take(std::size_t n, const char* field) {
    if (n > remaining())
      throw InputError(name_ + ": truncated " + what_ + ": " + field + " needs " + std::to_string(n) + " bytes at offset " +
                      std::to_string(pos_) + ", only " + std::to_string(remaining()) + " left");
    const auto s = bytes_.subspan(pos_, n);
    pos_ += n;
    return s;
  }
  std::uint8_t u8(const char* field) { return take(1, field)[0]; }
  std::uint16_t u16(const char* field) { return static_cast<std::uint16_t>(le(2, field)); }
  std::uint32_t u32(const char* field) { return static_cast<std::uint32_t>(le(4, field)); }
  std::uint64_t u64(const char* field) { return le(8, field); }
  std::int32_t i32(const char* field) { return static_cast<std::int32_t>(u32(field)); }
  float f32(const char* field) { return std::bit_cast<float>(u32(field)); }
  double f64(const char* field) { return std::bit_cast<double>(u64(field)); }
  std::string str(const char* field) {
    const std::uint32_t n = u32(field);
    const auto s = take(n, field);
    return {reinterpret_cast<const char*>(s.data()), s.size()};
  }
  // Values stored as planes: element `i` of a plane of u16 starting at `plane`.
  static std::uint16_t u16_at(std::span<const std::uint8_t> plane, std::size_t i) {
    return static_cast<std::uint16_t>(plane[2 * i] | (plane[2 * i + 1] << 8));
  }

 private:
  std::uint64_t le(int n, const char* field) {
    const auto s = take(static_cast<std::size_t>(n), field);
    std::uint64_t v = 0;
    for (int i = n - 1; i >= 0; --i) v = (v << 8) | s[static_cast<std::size_t>(i)];
    return v;
  }
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
  std::string name_;
  std::string what_;
};

}  // namespace dsswarm
