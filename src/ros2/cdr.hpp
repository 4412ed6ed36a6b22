#pragma once
// Plain CDR as ROS 2 puts it on the wire and in bags (XCDR1, little endian):
// a 4-byte encapsulation header 00 01 00 00, then the fields in order, each
// primitive aligned to its own size counted from the end of that header;
// strings are a uint32 length that includes the terminating NUL, the bytes and
// the NUL; sequences a uint32 element count and the elements; fixed arrays the
// elements only.
//
// The reader trusts nothing: every length is checked against the bytes left
// (and strings against a cap) before anything is allocated, and every problem
// is an InputError naming the message type, the field and the byte offset.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace dsswarm::ros2 {

// Encapsulation identifier CDR_LE with zero options.
inline constexpr std::uint8_t kCdrLeHeader[4] = {0x00, 0x01, 0x00, 0x00};

// No frame id comes near this; a longer string is damage, not data.
inline constexpr std::size_t kMaxCdrStringBytes = 64 * 1024;

// CDR pads a message to a multiple of 4 bytes at most (some writers do, some
// do not); more bytes left over mean the data is not the type being decoded.
inline constexpr std::size_t kMaxCdrTrailingBytes = 3;

class CdrWriter {
 public:
  CdrWriter();  // starts with the encapsulation header

  // Primitive types: int8/uint8, int32/uint32, float, double.
  template <typename T>
  void put(T value);
  void put_string(std::string_view s);
  void put_sequence_length(std::size_t n);
  // The elements of a sequence or fixed-size array.
  template <typename T>
  void put_elements(std::span<const T> values);

  std::vector<std::uint8_t> finish() &&;

 private:
  void align(std::size_t n);
  std::vector<std::uint8_t> bytes_;
};

class CdrReader {
 public:
  // Checks the encapsulation header. `type` names the message in errors.
  CdrReader(std::span<const std::uint8_t> bytes, std::string_view type);

  // The field names given here and by the enclosing scopes make up the path
  // an error names ("header.frame_id", "transforms[2].child_frame_id").
  template <typename T>
  T get(std::string_view field);
  std::string get_string(std::string_view field);
  // A sequence's element count, refused when fewer than `count *
  // min_element_bytes` bytes are left: nothing is sized from a damaged count.
  std::size_t get_sequence_length(std::string_view field, std::size_t min_element_bytes);
  template <typename T>
  void get_elements(std::string_view field, std::span<T> out);

  // Throws unless everything but trailing padding was read.
  void finish() const;

  // Names the fields read while it lives (a struct member or a sequence element).
  class Scope {
   public:
    Scope(CdrReader& reader, std::string name);
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    CdrReader& reader_;
  };

 private:
  [[noreturn]] void fail(std::string_view field, const std::string& what) const;
  std::span<const std::uint8_t> take(std::size_t n, std::size_t alignment, std::string_view field);

  std::span<const std::uint8_t> payload_;  // after the encapsulation header
  std::size_t pos_ = 0;                    // in payload_
  std::string type_;
  std::vector<std::string> path_;
};

}  // namespace dsswarm::ros2
