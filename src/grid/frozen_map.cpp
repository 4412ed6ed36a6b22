#include "grid/frozen_map.hpp"

#include <zstd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

constexpr int kCells = FrozenMap::kBlock * FrozenMap::kBlock;
constexpr int kZstdLevel = 1;  // fast: a submap is frozen while the robot drives on

std::uint8_t encode(float m) {
  // Rounded half up, as std::lround rounds a value >= 0, without its libm
  // call (a frozen submap encodes two masses per cell): the integer part
  // and the fraction of a float below 256 are both exact.
  const float v = 255.0f * std::sqrt(std::clamp(m, 0.0f, 1.0f));
  const auto whole = static_cast<int>(v);
  return static_cast<std::uint8_t>(whole + (v - static_cast<float>(whole) >= 0.5f ? 1 : 0));
}
float decode(std::uint8_t q) {
  const float r = static_cast<float>(q) / 255.0f;
  return r * r;
}

// encode() of every 16-bit mass a cell can hold, worked out once (64 KiB):
// freezing a submap encodes two masses per cell on the scan thread.
const std::array<std::uint8_t, 65536>& encoded() {
  static const std::array<std::uint8_t, 65536> table = [] {
    std::array<std::uint8_t, 65536> t{};
    for (std::uint32_t q = 0; q < t.size(); ++q)
      t[q] = encode(static_cast<float>(q) * (1.0f / PackedMass::kOne));  // as PackedMass::mass() decodes
    return t;
  }();
  return table;
}

// decode() of every byte, worked out once: thawing reads two per cell.
const std::array<float, 256>& decoded() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int q = 0; q < 256; ++q) t[static_cast<std::size_t>(q)] = decode(static_cast<std::uint8_t>(q));
    return t;
  }();
  return table;
}

// One block's cells into the grid: one tile lookup per block (a block lies in
// one tile), none for a block whose cells all hold nothing.
void unpack_block(DsGrid& grid, CellIndex origin, const std::uint8_t* occupied, const std::uint8_t* free) {
  static_assert(DsGrid::kTileSize % FrozenMap::kBlock == 0);
  if ((origin.x & (FrozenMap::kBlock - 1)) != 0 || (origin.y & (FrozenMap::kBlock - 1)) != 0)
    throw std::logic_error("FrozenMap: a block origin off the block grid");  // pack() writes aligned ones only
  const std::array<float, 256>& value = decoded();
  PackedMass* tile = nullptr;
  const int base = DsGrid::local_index(origin);
  for (int k = 0; k < kCells; ++k) {
    const std::uint8_t qo = occupied[k];
    const std::uint8_t qf = free[k];
    if (qo == 0 && qf == 0) continue;
    if (!tile) tile = grid.mutable_tile_cells(origin);
    const float o = value[qo];
    tile[base + (k / FrozenMap::kBlock) * DsGrid::kTileSize + k % FrozenMap::kBlock] =
        PackedMass::pack({o, std::min(value[qf], 1.0f - o)});
  }
}

// One level's evidence as [origins][occupied bytes][free bytes], blocks with evidence only.
std::vector<std::uint8_t> pack(const DsGrid& grid, std::size_t& blocks) {
  constexpr int per_tile = DsGrid::kTileSize / FrozenMap::kBlock;
  std::vector<CellIndex> origins;
  std::vector<std::uint8_t> occupied, free;
  std::uint8_t o[kCells], f[kCells];
  const std::array<std::uint8_t, 65536>& byte = encoded();
  grid.for_each_tile([&](CellIndex origin, const PackedMass* cells) {
    for (int by = 0; by < per_tile; ++by)
      for (int bx = 0; bx < per_tile; ++bx) {
        bool any = false;
        for (int y = 0; y < FrozenMap::kBlock; ++y)
          for (int x = 0; x < FrozenMap::kBlock; ++x) {
            const PackedMass m = cells[(by * FrozenMap::kBlock + y) * DsGrid::kTileSize + bx * FrozenMap::kBlock + x];
            const int k = y * FrozenMap::kBlock + x;
            o[k] = byte[m.occupied];
            // mass() caps free at 1 - occupied; below a full sum the cap changes nothing.
            f[k] = m.occupied + m.free < 65535u ? byte[m.free] : encode(m.mass().free);
            any = any || o[k] != 0 || f[k] != 0;
          }
        if (!any) continue;
        origins.push_back({origin.x + bx * FrozenMap::kBlock, origin.y + by * FrozenMap::kBlock});
        occupied.insert(occupied.end(), o, o + kCells);
        free.insert(free.end(), f, f + kCells);
      }
  });
  blocks = origins.size();
  std::vector<std::uint8_t> raw(origins.size() * sizeof(CellIndex));
  if (!raw.empty()) std::memcpy(raw.data(), origins.data(), raw.size());
  raw.insert(raw.end(), occupied.begin(), occupied.end());
  raw.insert(raw.end(), free.begin(), free.end());
  return raw;
}

}  // namespace

FrozenMap::FrozenMap(const MultiResMap& map) {
  static_assert(DsGrid::kTileSize % kBlock == 0);
  map.finest().bounds(bounds_min_, bounds_max_);
  for (int l = 0; l < map.levels(); ++l) {
    Level level;
    const std::vector<std::uint8_t> raw = pack(map.level(l), level.blocks);
    level.raw_bytes = raw.size();
    level.compressed.resize(ZSTD_compressBound(raw.size()));
    const std::size_t n = ZSTD_compress(level.compressed.data(), level.compressed.size(), raw.data(), raw.size(), kZstdLevel);
    if (ZSTD_isError(n)) throw std::runtime_error(std::string("FrozenMap: zstd: ") + ZSTD_getErrorName(n));
    level.compressed.resize(n);
    level.compressed.shrink_to_fit();
    levels_.push_back(std::move(level));
  }
}

MultiResMap FrozenMap::thaw(const MapConfig& config) const { return thaw(config, nullptr, nullptr); }

MultiResMap FrozenMap::thaw(const MapConfig& config, CellIndex region_min, CellIndex region_max) const {
  return thaw(config, &region_min, &region_max);
}

MultiResMap FrozenMap::thaw(const MapConfig& config, const CellIndex* region_min, const CellIndex* region_max) const {
  MultiResMap map(config);
  if (map.levels() > static_cast<int>(levels_.size()))
    throw ConfigError("FrozenMap::thaw: the configuration has more levels than the frozen map");
  std::vector<std::uint8_t> raw;
  for (int l = 0; l < map.levels(); ++l) {
    const Level& level = levels_[static_cast<std::size_t>(l)];
    raw.resize(level.raw_bytes);
    const std::size_t n = ZSTD_decompress(raw.data(), raw.size(), level.compressed.data(), level.compressed.size());
    if (ZSTD_isError(n) || n != raw.size()) throw std::runtime_error("FrozenMap: corrupt compressed level");
    std::vector<CellIndex> origins(level.blocks);
    if (!origins.empty()) std::memcpy(origins.data(), raw.data(), origins.size() * sizeof(CellIndex));
    const std::uint8_t* occupied = raw.data() + origins.size() * sizeof(CellIndex);
    const std::uint8_t* free = occupied + origins.size() * kCells;
    DsGrid& grid = map.mutable_level(l);
    const std::int32_t scale = 1 << l;  // level l cells are 2^l finest cells wide
    for (std::size_t b = 0; b < origins.size(); ++b) {
      const CellIndex lo{origins[b].x * scale, origins[b].y * scale};
      const CellIndex hi{(origins[b].x + kBlock) * scale, (origins[b].y + kBlock) * scale};
      if (region_min && (hi.x <= region_min->x || hi.y <= region_min->y || lo.x >= region_max->x ||
                         lo.y >= region_max->y))
        continue;
      unpack_block(grid, origins[b], occupied + b * kCells, free + b * kCells);
    }
  }
  return map;
}

std::size_t FrozenMap::memory_bytes() const {
  std::size_t n = levels_.capacity() * sizeof(Level);
  for (const Level& l : levels_) n += l.compressed.capacity();
  return n;
}

}  // namespace dsswarm
