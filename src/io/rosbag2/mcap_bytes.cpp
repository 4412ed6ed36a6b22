#include "io/rosbag2/mcap_bytes.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <array>

#include "common/errors.hpp"

namespace dsswarm::mcap {

std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc) {
  return static_cast<std::uint32_t>(crc32_z(crc, bytes.data(), bytes.size()));
}

const char* op_name(Op op) {
  switch (op) {
    case Op::Header: return "Header";
    case Op::Footer: return "Footer";
    case Op::Schema: return "Schema";
    case Op::Channel: return "Channel";
    case Op::Message: return "Message";
    case Op::Chunk: return "Chunk";
    case Op::MessageIndex: return "MessageIndex";
    case Op::ChunkIndex: return "ChunkIndex";
    case Op::Attachment: return "Attachment";
    case Op::AttachmentIndex: return "AttachmentIndex";
    case Op::Statistics: return "Statistics";
    case Op::Metadata: return "Metadata";
    case Op::MetadataIndex: return "MetadataIndex";
    case Op::SummaryOffset: return "SummaryOffset";
    case Op::DataEnd: return "DataEnd";
  }
  return "unknown";
}

std::span<const std::uint8_t> Fields::take(std::uint64_t n, const char* field) {
  const std::size_t left = bytes_.size() - pos_;
  if (n > left) {
    throw InputError(fmt::format("{}: field {} needs {} bytes, the record has {} left", where_,
                                 field, n, left));
  }
  const auto out = bytes_.subspan(pos_, static_cast<std::size_t>(n));
  pos_ += static_cast<std::size_t>(n);
  return out;
}

void FileBytes::read(std::span<std::uint8_t> out, const std::string& what) {
  if (out.size() > left()) {
    throw InputError(fmt::format("{}: truncated: {} needs {} bytes, only {} are left", name_, what,
                                 out.size(), left()));
  }
  in_.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(out.size()));
  if (in_.gcount() != static_cast<std::streamsize>(out.size())) {
    throw InputError(fmt::format("{}: read error at byte {} ({})", name_, pos_, what));
  }
  crc_ = crc32(out, crc_);
  pos_ += out.size();
}

std::vector<std::uint8_t> FileBytes::read_vector(std::uint64_t n, const std::string& what) {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(n));
  read(out, what);
  return out;
}

void FileBytes::skip(std::uint64_t n, const std::string& what) {
  std::array<std::uint8_t, 1 << 16> piece{};
  while (n > 0) {
    const auto k = static_cast<std::size_t>(std::min<std::uint64_t>(n, piece.size()));
    read(std::span(piece.data(), k), what);
    n -= k;
  }
}

}  // namespace dsswarm::mcap
