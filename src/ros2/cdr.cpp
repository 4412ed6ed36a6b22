#include "ros2/cdr.hpp"

#include <fmt/format.h>

#include <bit>
#include <cstring>
#include <type_traits>

#include "common/errors.hpp"

namespace dsswarm::ros2 {
namespace {

// The unsigned integer with the bits of T, for byte-order-independent packing.
template <typename T>
using Bits = std::conditional_t<sizeof(T) == 1, std::uint8_t,
                                std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>;

template <typename T>
void store_le(std::uint8_t* out, T value) {
  auto bits = std::bit_cast<Bits<T>>(value);
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out[i] = static_cast<std::uint8_t>(bits & 0xFFU);
    if constexpr (sizeof(T) > 1) bits = static_cast<Bits<T>>(bits >> 8);
  }
}

template <typename T>
T load_le(const std::uint8_t* in) {
  Bits<T> bits = 0;
  for (std::size_t i = sizeof(T); i-- > 0;) {
    if constexpr (sizeof(T) > 1) bits = static_cast<Bits<T>>(bits << 8);
    bits = static_cast<Bits<T>>(bits | in[i]);
  }
  return std::bit_cast<T>(bits);
}

constexpr std::size_t padding_to(std::size_t pos, std::size_t alignment) {
  return (alignment - pos % alignment) % alignment;
}

}  // namespace

// ------------------------------------------------------------------ writer

CdrWriter::CdrWriter() : bytes_(std::begin(kCdrLeHeader), std::end(kCdrLeHeader)) {}

void CdrWriter::align(std::size_t n) {
  bytes_.resize(bytes_.size() + padding_to(bytes_.size() - sizeof(kCdrLeHeader), n), 0);
}

template <typename T>
void CdrWriter::put(T value) {
  align(sizeof(T));
  const std::size_t at = bytes_.size();
  bytes_.resize(at + sizeof(T));
  store_le(bytes_.data() + at, value);
}

void CdrWriter::put_string(std::string_view s) {
  put(static_cast<std::uint32_t>(s.size() + 1));
  bytes_.insert(bytes_.end(), s.begin(), s.end());
  bytes_.push_back(0);
}

void CdrWriter::put_sequence_length(std::size_t n) { put(static_cast<std::uint32_t>(n)); }

template <typename T>
void CdrWriter::put_elements(std::span<const T> values) {
  if (values.empty()) return;  // an empty sequence adds no padding
  align(sizeof(T));
  std::size_t at = bytes_.size();
  bytes_.resize(at + values.size() * sizeof(T));
  for (const T v : values) {
    store_le(bytes_.data() + at, v);
    at += sizeof(T);
  }
}

std::vector<std::uint8_t> CdrWriter::finish() && { return std::move(bytes_); }

// ------------------------------------------------------------------ reader

CdrReader::CdrReader(std::span<const std::uint8_t> bytes, std::string_view type) : type_(type) {
  if (bytes.size() < sizeof(kCdrLeHeader)) {
    throw InputError(fmt::format("{}: {} bytes, too short for a CDR encapsulation header", type_,
                                 bytes.size()));
  }
  if (bytes[0] != kCdrLeHeader[0] || bytes[1] != kCdrLeHeader[1]) {
    const char* kind = bytes[0] == 0x00 && bytes[1] == 0x00 ? " (big-endian CDR)" : "";
    throw InputError(fmt::format("{}: encapsulation {:02x} {:02x}{} is not little-endian plain "
                                 "CDR (00 01), the only one ROS 2 writes here",
                                 type_, bytes[0], bytes[1], kind));
  }
  payload_ = bytes.subspan(sizeof(kCdrLeHeader));
}

CdrReader::Scope::Scope(CdrReader& reader, std::string name) : reader_(reader) {
  reader_.path_.push_back(std::move(name));
}

CdrReader::Scope::~Scope() { reader_.path_.pop_back(); }

void CdrReader::fail(std::string_view field, const std::string& what) const {
  std::string path;
  const auto append = [&path](std::string_view part) {
    if (!path.empty() && part.front() != '[') path.push_back('.');
    path.append(part);
  };
  for (const std::string& part : path_) append(part);
  if (!field.empty()) append(field);
  throw InputError(fmt::format("{}: field {}: {} (at byte {} of {})", type_, path, what,
                               pos_ + sizeof(kCdrLeHeader),
                               payload_.size() + sizeof(kCdrLeHeader)));
}

std::span<const std::uint8_t> CdrReader::take(std::size_t n, std::size_t alignment,
                                              std::string_view field) {
  const std::size_t left = payload_.size() - pos_;
  const std::size_t pad = padding_to(pos_, alignment);
  if (pad > left || n > left - pad) {
    fail(field, fmt::format("needs {} bytes, the message ends after {}", pad + n, left));
  }
  pos_ += pad;
  const auto out = payload_.subspan(pos_, n);
  pos_ += n;
  return out;
}

template <typename T>
T CdrReader::get(std::string_view field) {
  return load_le<T>(take(sizeof(T), sizeof(T), field).data());
}

std::string CdrReader::get_string(std::string_view field) {
  const auto length = get<std::uint32_t>(field);
  if (length == 0) return {};  // not what CDR specifies, but harmless to accept
  if (length > kMaxCdrStringBytes) {
    fail(field, fmt::format("string length {} exceeds the cap of {} bytes", length,
                            kMaxCdrStringBytes));
  }
  const auto bytes = take(length, 1, field);
  if (bytes.back() != 0) fail(field, "string is not NUL-terminated");
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size() - 1};
}

std::size_t CdrReader::get_sequence_length(std::string_view field, std::size_t min_element_bytes) {
  const auto count = get<std::uint32_t>(field);
  const std::size_t left = payload_.size() - pos_;
  if (min_element_bytes > 0 && count > left / min_element_bytes) {
    fail(field, fmt::format("sequence of {} elements needs at least {} bytes, {} are left", count,
                            std::size_t{count} * min_element_bytes, left));
  }
  return count;
}

template <typename T>
void CdrReader::get_elements(std::string_view field, std::span<T> out) {
  if (out.empty()) return;
  const auto bytes = take(out.size() * sizeof(T), sizeof(T), field);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = load_le<T>(bytes.data() + i * sizeof(T));
}

void CdrReader::finish() const {
  const std::size_t left = payload_.size() - pos_;
  if (left > kMaxCdrTrailingBytes) {
    throw InputError(fmt::format("{}: {} bytes left over after the last field (at byte {} of {}): "
                                 "the data is not this message type",
                                 type_, left, pos_ + sizeof(kCdrLeHeader),
                                 payload_.size() + sizeof(kCdrLeHeader)));
  }
}

// The primitive types ROS 2 messages here are made of.
#define DSSWARM_CDR_PRIMITIVE(T)                                          \
  template void CdrWriter::put<T>(T);                                     \
  template void CdrWriter::put_elements<T>(std::span<const T>);           \
  template T CdrReader::get<T>(std::string_view);                         \
  template void CdrReader::get_elements<T>(std::string_view, std::span<T>);
DSSWARM_CDR_PRIMITIVE(std::int8_t)
DSSWARM_CDR_PRIMITIVE(std::uint8_t)
DSSWARM_CDR_PRIMITIVE(std::int32_t)
DSSWARM_CDR_PRIMITIVE(std::uint32_t)
DSSWARM_CDR_PRIMITIVE(float)
DSSWARM_CDR_PRIMITIVE(double)
#undef DSSWARM_CDR_PRIMITIVE

}  // namespace dsswarm::ros2
