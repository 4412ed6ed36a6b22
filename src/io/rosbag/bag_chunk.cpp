#include "io/rosbag/bag_chunk.hpp"

#include <bzlib.h>
#include <roslz4/lz4s.h>

#include <algorithm>
#include <cstddef>

namespace dsswarm::rosbag_raw {
namespace {

constexpr std::uint32_t kMaxChunkSize = 1U << 30;  // rosbag writes ~768 kB chunks

// bz2 can shrink data by far more than any fixed ratio, so its output
// grows a step at a time, to at most one byte more than `size` (which
// tells a chunk holding more than it says).
std::vector<char> inflate_bz2(const std::string& path, std::vector<char>& in, std::uint32_t size,
                              std::uint64_t pos) {
  constexpr std::size_t kStep = 1 << 20;
  bz_stream stream{};
  if (BZ2_bzDecompressInit(&stream, 0, 0) != BZ_OK)
    damaged_record(path, "libbz2 cannot start", pos);
  stream.next_in = in.data();
  stream.avail_in = static_cast<unsigned int>(in.size());
  std::vector<char> out;
  std::size_t produced = 0;
  int rc = BZ_OK;
  while (rc == BZ_OK && produced <= size) {
    if (produced == out.size()) out.resize(std::min<std::size_t>(std::size_t{size} + 1, out.size() + kStep));
    stream.next_out = out.data() + produced;
    stream.avail_out = static_cast<unsigned int>(out.size() - produced);
    const std::size_t before = produced;
    rc = BZ2_bzDecompress(&stream);
    produced = out.size() - stream.avail_out;
    if (rc == BZ_OK && stream.avail_in == 0 && produced == before) rc = BZ_UNEXPECTED_EOF;
  }
  BZ2_bzDecompressEnd(&stream);
  if (rc != BZ_STREAM_END && produced <= size)
    damaged_record(path, "corrupt bz2 chunk (libbz2 error " + std::to_string(rc) + ")", pos);
  out.resize(produced);
  return out;
}

}  // namespace

std::vector<char> decompress_chunk(const std::string& path, const Fields& fields,
                                   const std::string& data, std::uint64_t pos) {
  const auto compression = fields.find("compression");
  const auto size = static_cast<std::uint32_t>(fixed_size_field(path, fields, "size", 4, pos));
  if (compression == fields.end()) damaged_record(path, "chunk without a compression field", pos);
  if (size > kMaxChunkSize)
    damaged_record(path, "implausible chunk size " + std::to_string(size), pos);
  std::vector<char> in(data.begin(), data.end());  // the C APIs take non-const pointers
  std::vector<char> out;
  if (compression->second == "none") {
    if (data.size() != size)
      damaged_record(path, "uncompressed chunk whose size field disagrees with its length", pos);
    return in;
  } else if (compression->second == "bz2") {
    out = inflate_bz2(path, in, size, pos);
  } else if (compression->second == "lz4") {
    // An LZ4 byte stands for at most 255 output bytes.
    constexpr std::uint64_t kMaxLz4Ratio = 255, kLz4FrameSlack = 1 << 16;
    if (size > kMaxLz4Ratio * in.size() + kLz4FrameSlack) {
      damaged_record(path,
                     "lz4 chunk of " + std::to_string(in.size()) + " bytes cannot hold the " +
                         std::to_string(size) + " bytes its header says",
                     pos);
    }
    out.resize(size);
    unsigned int out_size = size;
    const int rc = roslz4_buffToBuffDecompress(in.data(), static_cast<unsigned int>(in.size()),
                                               out.data(), &out_size);
    if (rc != ROSLZ4_OK)
      damaged_record(path, "corrupt lz4 chunk (roslz4 error " + std::to_string(rc) + ")", pos);
    out.resize(out_size);
  } else {
    damaged_record(path, "unknown chunk compression '" + compression->second + "'", pos);
  }
  if (out.size() != size) {
    damaged_record(path,
                   "chunk decompresses to " +
                       (out.size() > size ? "more than " + std::to_string(size) + " bytes"
                                          : std::to_string(out.size()) + " bytes") +
                       ", its header says " + std::to_string(size),
                   pos);
  }
  return out;
}

}  // namespace dsswarm::rosbag_raw
