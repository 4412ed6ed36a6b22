#include "protocol/transfer.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <stdexcept>

#include "protocol/wire.hpp"

namespace dsswarm::protocol {

std::vector<Chunk> split_transfer(std::uint64_t encounter, std::span<const std::uint8_t> bytes,
                                  std::size_t chunk_bytes) {
  if (chunk_bytes == 0) throw std::invalid_argument("split_transfer: chunk size 0");
  std::vector<Chunk> out;
  if (bytes.empty()) {
    out.push_back(Chunk{encounter, 0, 0, 0, 0, {}});
    return out;
  }
  const auto crc = static_cast<std::uint32_t>(crc32_z(0, bytes.data(), bytes.size()));
  const std::size_t count = (bytes.size() + chunk_bytes - 1) / chunk_bytes;
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t begin = i * chunk_bytes, end = std::min(bytes.size(), begin + chunk_bytes);
    out.push_back(Chunk{encounter, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(count), bytes.size(),
                        crc, std::vector<std::uint8_t>(bytes.begin() + static_cast<std::ptrdiff_t>(begin),
                                                       bytes.begin() + static_cast<std::ptrdiff_t>(end))});
  }
  return out;
}

bool TransferAssembler::add(const Chunk& c) {
  if (!started_) {
    started_ = true;
    count_ = c.count;
    total_ = c.total_bytes;
    crc_ = c.total_crc;
    parts_.resize(count_);
  } else if (c.count != count_ || c.total_bytes != total_ || c.total_crc != crc_) {
    throw ProtocolError(fmt::format("chunk {} says {} chunks / {} bytes, earlier chunks said {} / {}", c.index,
                                    c.count, c.total_bytes, count_, total_));
  }
  if (count_ == 0) return true;
  if (c.index >= count_) throw ProtocolError(fmt::format("chunk {} of {} is out of range", c.index, count_));
  std::vector<std::uint8_t>& part = parts_[c.index];
  if (!part.empty() || c.data.empty()) {
    if (c.data.empty()) throw ProtocolError(fmt::format("chunk {} of {} is empty", c.index, count_));
    return complete();  // a repeat
  }
  if (bytes_ + c.data.size() > total_)
    throw ProtocolError(fmt::format("chunks add up to more than the {} bytes declared", total_));
  part = c.data;
  bytes_ += part.size();
  ++received_;
  if (received_ == count_ && bytes_ != total_)
    throw ProtocolError(fmt::format("{} chunks hold {} bytes, {} declared", count_, bytes_, total_));
  return complete();
}

std::vector<std::uint8_t> TransferAssembler::take() {
  if (!complete()) throw std::logic_error("TransferAssembler::take before the transfer is complete");
  std::vector<std::uint8_t> whole;
  whole.reserve(bytes_);
  for (auto& p : parts_) {
    whole.insert(whole.end(), p.begin(), p.end());
    std::vector<std::uint8_t>().swap(p);
  }
  if (count_ > 0 && static_cast<std::uint32_t>(crc32_z(0, whole.data(), whole.size())) != crc_)
    throw ProtocolError("transfer checksum mismatch: the snapshot arrived corrupt");
  return whole;
}

}  // namespace dsswarm::protocol
