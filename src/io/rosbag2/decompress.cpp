#include "io/rosbag2/decompress.hpp"

#include <fmt/format.h>
#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <memory>

#include "common/errors.hpp"

namespace dsswarm::rosbag2 {
namespace {

constexpr std::size_t kMinGrowth = std::size_t{1} << 20;

// Output space that grows with use up to one byte past the limit, so that
// "more than the limit" shows as produced > max_bytes.
class GrowingOutput {
 public:
  GrowingOutput(std::size_t max_bytes, const std::string& what) : max_(max_bytes), what_(what) {}

  // Makes room if the buffer is full; throws once the limit is passed.
  void make_room() {
    if (produced_ < bytes_.size()) return;
    if (bytes_.size() > max_) {
      throw InputError(fmt::format("{}: decompresses to more than {} bytes", what_, max_));
    }
    bytes_.resize(std::min(max_ + 1, bytes_.size() + std::max(kMinGrowth, bytes_.size())));
  }
  std::uint8_t* free_begin() { return bytes_.data() + produced_; }
  std::size_t free_size() const { return bytes_.size() - produced_; }
  void produced(std::size_t n) { produced_ += n; }

  std::vector<std::uint8_t> finish() && {
    if (produced_ > max_) {
      throw InputError(fmt::format("{}: decompresses to more than {} bytes", what_, max_));
    }
    bytes_.resize(produced_);
    return std::move(bytes_);
  }

 private:
  std::size_t max_;
  const std::string& what_;
  std::vector<std::uint8_t> bytes_;
  std::size_t produced_ = 0;
};

[[noreturn]] void truncated(const std::string& what, const char* format) {
  throw InputError(fmt::format("{}: {} data ends in the middle of a frame", what, format));
}

}  // namespace

std::vector<std::uint8_t> zstd_decompress(std::span<const std::uint8_t> in, std::size_t max_bytes,
                                          const std::string& what) {
  const std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> context(ZSTD_createDCtx(),
                                                                      &ZSTD_freeDCtx);
  if (!context) throw std::bad_alloc();
  GrowingOutput out(max_bytes, what);
  ZSTD_inBuffer input{in.data(), in.size(), 0};
  for (;;) {
    out.make_room();
    ZSTD_outBuffer output{out.free_begin(), out.free_size(), 0};
    const std::size_t hint = ZSTD_decompressStream(context.get(), &output, &input);
    if (ZSTD_isError(hint)) {
      throw InputError(fmt::format("{}: damaged zstd data ({})", what, ZSTD_getErrorName(hint)));
    }
    out.produced(output.pos);
    if (input.pos < input.size) continue;
    if (hint == 0) break;                              // every frame complete
    if (out.free_size() > 0) truncated(what, "zstd");  // room left, so it wants more input
  }
  return std::move(out).finish();
}

std::vector<std::uint8_t> lz4_frame_decompress(std::span<const std::uint8_t> in,
                                               std::size_t max_bytes, const std::string& what) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) throw std::bad_alloc();
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> context(
      raw, &LZ4F_freeDecompressionContext);
  GrowingOutput out(max_bytes, what);
  std::size_t in_pos = 0;
  for (;;) {
    out.make_room();
    std::size_t out_size = out.free_size();
    std::size_t in_size = in.size() - in_pos;
    const std::size_t hint = LZ4F_decompress(context.get(), out.free_begin(), &out_size,
                                             in.data() + in_pos, &in_size, nullptr);
    if (LZ4F_isError(hint)) {
      throw InputError(fmt::format("{}: damaged lz4 data ({})", what, LZ4F_getErrorName(hint)));
    }
    out.produced(out_size);
    in_pos += in_size;
    if (in_pos < in.size()) continue;
    if (hint == 0) break;                             // the last frame is complete
    if (out.free_size() > 0) truncated(what, "lz4");  // room left, so it wants more input
  }
  return std::move(out).finish();
}

}  // namespace dsswarm::rosbag2
