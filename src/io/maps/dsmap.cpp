#include "io/maps/dsmap.hpp"

#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string_view>

#include "common/errors.hpp"
#include "common/byte_io.hpp"
#include "io/atomic_file.hpp"

namespace dsswarm {
namespace {

constexpr std::string_view kMagic = "DSMAP";
constexpr std::uint16_t kFirstVersionWithPieces = 2;  // layers carry submap pieces from this version on
constexpr std::size_t kHeaderBytes = 5 + 2 + 4 + 4 + 8 + 8;  // magic, version, 2 CRCs, 2 sizes
// Level 3 (zstd's default): on the simulated building, 9 is 5% smaller for
// 7× the time, 19 is 15% smaller for 200× the time.
constexpr int kZstdLevel = 3;
constexpr std::size_t kTileCells = DsGrid::kTileCells;
constexpr std::size_t kTileBytes = 2 * 4 + 2 * 2 * kTileCells;  // origin + two u16 planes
// Limits that keep garbage from allocating absurd memory. A zstd block
// expands at most 128 KiB from 4 bytes (32768×), so a payload declared larger
// than 65536× its compressed size cannot be genuine.
constexpr std::uint64_t kMaxPayloadBytes = std::uint64_t{1} << 30;
constexpr std::uint64_t kMaxExpansion = 65536;
// Tile coordinates whose cells still fit in int32, and a bound on a level's
// tile bounding box (DsGrid keeps a dense pointer table over it): 2048² tiles
// is a 6.5 km square at 5 cm.
constexpr std::int64_t kMaxTileIndex = (std::int64_t{1} << (31 - DsGrid::kTileBits)) - 1;
constexpr std::int64_t kMaxTileArea = std::int64_t{1} << 22;
constexpr int kMinLevels = 1, kMaxLevels = 6;  // as MapConfig::validate
constexpr double kMinResolution = 0.005, kMaxResolution = 2.0;

[[noreturn]] void fail(const std::string& name, const std::string& what) { throw InputError(name + ": " + what); }

// ---- encoding -------------------------------------------------------------

void encode_level(ByteWriter& w, const DsGrid& grid) {
  struct StoredTile {
    CellIndex origin;
    const PackedMass* cells;
  };
  std::vector<StoredTile> tiles;
  grid.for_each_tile([&](CellIndex origin, const PackedMass* cells) {
    const bool any = std::any_of(cells, cells + kTileCells, [](const PackedMass& m) { return !m.vacuous(); });
    if (any) tiles.push_back({origin, cells});
  });
  // Tiles in raster order: the same map always gives the same bytes, and
  // neighbouring tiles (similar content) sit together for the compressor.
  std::sort(tiles.begin(), tiles.end(), [](const StoredTile& a, const StoredTile& b) {
    return a.origin.y != b.origin.y ? a.origin.y < b.origin.y : a.origin.x < b.origin.x;
  });
  w.u32(static_cast<std::uint32_t>(tiles.size()));
  for (const StoredTile& t : tiles) {
    w.i32(t.origin.x >> DsGrid::kTileBits);
    w.i32(t.origin.y >> DsGrid::kTileBits);
  }
  for (const StoredTile& t : tiles)
    for (std::size_t i = 0; i < kTileCells; ++i) w.u16(t.cells[i].occupied);
  // The grid's own 16-bit cells: stored as they are, free <= 1 - occupied holds.
  for (const StoredTile& t : tiles)
    for (std::size_t i = 0; i < kTileCells; ++i) w.u16(t.cells[i].free);
}

void encode_levels(ByteWriter& w, const MultiResMap& map) {
  w.u8(static_cast<std::uint8_t>(map.levels()));
  for (int l = 0; l < map.levels(); ++l) encode_level(w, map.level(l));
}

void write_pose(ByteWriter& w, const Pose2& p) {
  w.f64(p.x);
  w.f64(p.y);
  w.f64(p.theta);
}

std::vector<std::uint8_t> encode_payload(const MapSnapshot& snapshot, std::uint16_t format_version) {
  MapConfig config;  // an empty snapshot still names a valid configuration
  if (!snapshot.layers.empty()) {
    for (std::size_t i = 0; i < snapshot.layers.size(); ++i)
      if (!snapshot.layers[i].map) throw std::invalid_argument("encode_dsmap: layer " + std::to_string(i) + " has no map");
    config = snapshot.layers.front().map->config();
    for (std::size_t i = 1; i < snapshot.layers.size(); ++i) {
      const MultiResMap& m = *snapshot.layers[i].map;
      if (m.config().resolution != config.resolution || m.levels() != config.levels)
        throw std::invalid_argument("encode_dsmap: layer " + std::to_string(i) +
                                    " has a different resolution or level count from layer 0");
    }
  }
  ByteWriter w;
  std::size_t cells = 0;
  for (const MapLayer& layer : snapshot.layers) cells += layer.map->cells_allocated();
  w.reserve(256 + 4 * cells);
  w.f64(config.resolution);
  w.u8(static_cast<std::uint8_t>(config.levels));
  w.f32(config.evidence.hit_occupied);
  w.f32(config.evidence.pass_free);
  w.f32(config.evidence.min_unknown);
  w.str(snapshot.sender);
  w.u32(static_cast<std::uint32_t>(snapshot.layers.size()));
  for (const MapLayer& layer : snapshot.layers) {
    w.str(layer.origin);
    w.u64(layer.version);
    write_pose(w, layer.origin_in_holder);
    w.i32(layer.hops);
    encode_levels(w, *layer.map);
    if (format_version < kFirstVersionWithPieces) {
      if (!layer.pieces.empty()) throw std::invalid_argument("encode_dsmap: format version 1 holds no submap pieces");
      continue;
    }
    w.u32(static_cast<std::uint32_t>(layer.pieces.size()));
    for (const MapPiece& piece : layer.pieces) {
      if (!piece.map) throw std::invalid_argument("encode_dsmap: a piece of layer '" + layer.origin + "' has no map");
      w.i32(piece.id);
      write_pose(w, piece.pose);
      encode_levels(w, piece.map->thaw(config));
    }
  }
  return std::move(w.bytes());
}

// ---- decoding -------------------------------------------------------------

void decode_level(ByteReader& r, DsGrid& grid, const std::string& name, const std::string& where) {
  const std::uint32_t count = r.u32("tile count");
  if (count > r.remaining() / kTileBytes)
    fail(name, where + ": " + std::to_string(count) + " tiles need " + std::to_string(count * kTileBytes) +
                   " bytes, only " + std::to_string(r.remaining()) + " left in the payload");
  const auto origins = r.take(std::size_t{8} * count, "tile origins");
  std::vector<std::pair<std::int32_t, std::int32_t>> tiles(count);
  for (std::size_t t = 0; t < count; ++t) {
    auto i32_at = [&](std::size_t k) {  // k-th little-endian int32 of the origins
      std::uint32_t v = 0;
      for (std::size_t b = 4; b-- > 0;) v = (v << 8) | origins[4 * k + b];
      return static_cast<std::int32_t>(v);
    };
    tiles[t] = {i32_at(2 * t), i32_at(2 * t + 1)};
    for (const std::int32_t c : {tiles[t].first, tiles[t].second})
      if (c < -kMaxTileIndex - 1 || c > kMaxTileIndex)
        fail(name, where + ": tile " + std::to_string(t) + " lies at tile coordinate " + std::to_string(c) +
                       ", outside the int32 cell range");
  }
  if (count > 0) {
    // The grid keeps a dense table over the tiles' bounding box: bound it
    // before creating any tile, and refuse the same tile twice.
    auto sorted = tiles;
    std::sort(sorted.begin(), sorted.end());
    if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end())
      fail(name, where + ": tile (" + std::to_string(twice->first) + ", " + std::to_string(twice->second) +
                     ") appears twice");
    std::int64_t min_x = sorted.front().first, max_x = sorted.back().first;
    std::int64_t min_y = tiles.front().second, max_y = min_y;
    for (const auto& t : tiles) {
      min_y = std::min<std::int64_t>(min_y, t.second);
      max_y = std::max<std::int64_t>(max_y, t.second);
    }
    const std::int64_t width = max_x - min_x + 1, height = max_y - min_y + 1;
    if (width > kMaxTileArea / height)
      fail(name, where + ": tiles spread over " + std::to_string(width) + " × " + std::to_string(height) +
                     " tiles, more than this reader accepts (" + std::to_string(kMaxTileArea) + " tiles)");
  }
  const auto occupied = r.take(2 * kTileCells * count, "occupied masses");
  const auto free = r.take(2 * kTileCells * count, "free masses");
  for (std::size_t t = 0; t < count; ++t) {
    const std::int32_t x0 = tiles[t].first * DsGrid::kTileSize, y0 = tiles[t].second * DsGrid::kTileSize;
    for (std::size_t i = 0; i < kTileCells; ++i) {
      const std::uint16_t qo = ByteReader::u16_at(occupied, t * kTileCells + i);
      const std::uint16_t qf = ByteReader::u16_at(free, t * kTileCells + i);
      const CellIndex cell{x0 + static_cast<std::int32_t>(i % DsGrid::kTileSize),
                           y0 + static_cast<std::int32_t>(i / DsGrid::kTileSize)};
      if (std::uint32_t{qo} + qf > 65535)
        fail(name, where + ": cell (" + std::to_string(cell.x) + ", " + std::to_string(cell.y) +
                       ") has occupied + free mass above 1 (" + std::to_string(qo) + " + " + std::to_string(qf) +
                       " of 65535)");
      if (qo == 0 && qf == 0) continue;  // vacuous: nothing to store
      grid.set_packed(cell, {qo, qf});
    }
  }
}

std::shared_ptr<MultiResMap> decode_levels(ByteReader& r, const MapConfig& config, const std::string& name,
                                           const std::string& where) {
  const int levels = r.u8("levels");
  if (levels != config.levels)
    fail(name, where + " has " + std::to_string(levels) + " levels, the header says " + std::to_string(config.levels));
  auto map = std::make_shared<MultiResMap>(config);
  for (int l = 0; l < levels; ++l) decode_level(r, map->mutable_level(l), name, where + " level " + std::to_string(l));
  return map;
}

Pose2 read_pose(ByteReader& r, const std::string& name, const std::string& where) {
  const double x = r.f64("pose x"), y = r.f64("pose y"), theta = r.f64("pose theta");
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(theta))
    fail(name, where + ": pose (" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(theta) +
                   ") is not finite");
  return Pose2(x, y, theta);
}

std::vector<MapPiece> decode_pieces(ByteReader& r, const MapConfig& config, const std::string& name,
                                    const std::string& where) {
  const std::uint32_t count = r.u32("piece count");
  const std::size_t min_piece_bytes = 4 + 3 * 8 + 1 + 4 * static_cast<std::size_t>(config.levels);
  if (count > r.remaining() / min_piece_bytes)
    fail(name, where + ": " + std::to_string(count) + " pieces cannot fit in the " + std::to_string(r.remaining()) +
                   " bytes left in the payload");
  std::vector<MapPiece> pieces;
  pieces.reserve(count);
  for (std::uint32_t k = 0; k < count; ++k) {
    const std::string at = where + " piece " + std::to_string(k);
    MapPiece piece;
    piece.id = r.i32("piece id");
    if (std::any_of(pieces.begin(), pieces.end(), [&](const MapPiece& p) { return p.id == piece.id; }))
      fail(name, at + ": piece id " + std::to_string(piece.id) + " appears twice");
    piece.pose = read_pose(r, name, at);
    piece.map = std::make_shared<const FrozenMap>(*decode_levels(r, config, name, at));
    pieces.push_back(std::move(piece));
  }
  return pieces;
}

MapSnapshot decode_payload(std::span<const std::uint8_t> payload, std::uint16_t format_version,
                           const std::string& name) {
  ByteReader r(payload, name, "payload");
  const bool version_has_pieces = format_version >= kFirstVersionWithPieces;
  MapConfig config;
  config.resolution = r.f64("resolution");
  if (!(config.resolution >= kMinResolution && config.resolution <= kMaxResolution))
    fail(name, "resolution " + std::to_string(config.resolution) + " m is outside [" + std::to_string(kMinResolution) +
                   ", " + std::to_string(kMaxResolution) + "]");
  config.levels = r.u8("levels");
  if (config.levels < kMinLevels || config.levels > kMaxLevels)
    fail(name, "level count " + std::to_string(config.levels) + " is outside [" + std::to_string(kMinLevels) + ", " +
                   std::to_string(kMaxLevels) + "]");
  config.evidence.hit_occupied = r.f32("evidence.hit_occupied");
  config.evidence.pass_free = r.f32("evidence.pass_free");
  config.evidence.min_unknown = r.f32("evidence.min_unknown");
  try {
    config.validate();
  } catch (const ConfigError& e) {
    fail(name, std::string("bad map header: ") + e.what());
  }

  MapSnapshot snapshot;
  snapshot.sender = r.str("sender");
  const std::uint32_t layers = r.u32("layer count");
  // Smallest possible layer: empty origin, no tiles on any level.
  const std::size_t min_layer_bytes =
      4 + 8 + 3 * 8 + 4 + 1 + 4 * static_cast<std::size_t>(config.levels) + (version_has_pieces ? 4 : 0);
  if (layers > r.remaining() / min_layer_bytes)
    fail(name, std::to_string(layers) + " layers cannot fit in the " + std::to_string(r.remaining()) +
                   " bytes left in the payload");
  snapshot.layers.reserve(layers);
  for (std::uint32_t i = 0; i < layers; ++i) {
    const std::string where = "layer " + std::to_string(i);
    MapLayer layer;
    layer.origin = r.str("layer origin");
    layer.version = r.u64("layer version");
    const std::string named = where + " ('" + layer.origin + "')";
    layer.origin_in_holder = read_pose(r, name, named);
    layer.hops = r.i32("layer hops");
    if (layer.hops < 0) fail(name, named + ": negative hop count " + std::to_string(layer.hops));
    layer.map = decode_levels(r, config, name, named);
    if (version_has_pieces) layer.pieces = decode_pieces(r, config, name, named);
    snapshot.layers.push_back(std::move(layer));
  }
  if (r.remaining() != 0)
    fail(name, std::to_string(r.remaining()) + " unexpected bytes after the last layer of the payload");
  return snapshot;
}

}  // namespace

std::vector<std::uint8_t> encode_dsmap(const MapSnapshot& snapshot, std::uint16_t format_version) {
  if (format_version < kDsmapOldestReadable || format_version > kDsmapFormatVersion)
    throw std::invalid_argument("encode_dsmap: no format version " + std::to_string(format_version));
  const std::vector<std::uint8_t> payload = encode_payload(snapshot, format_version);
  if (payload.size() > kMaxPayloadBytes)
    throw std::invalid_argument("encode_dsmap: the map needs " + std::to_string(payload.size()) +
                                " bytes, more than the format allows (" + std::to_string(kMaxPayloadBytes) + ")");
  std::vector<std::uint8_t> compressed(ZSTD_compressBound(payload.size()));
  const std::size_t csize = ZSTD_compress(compressed.data(), compressed.size(), payload.data(), payload.size(), kZstdLevel);
  if (ZSTD_isError(csize)) throw std::runtime_error(std::string("encode_dsmap: zstd: ") + ZSTD_getErrorName(csize));

  ByteWriter w;
  w.reserve(kHeaderBytes + csize);
  for (const char c : kMagic) w.u8(static_cast<std::uint8_t>(c));
  w.u16(format_version);
  w.u32(static_cast<std::uint32_t>(crc32_z(0, payload.data(), payload.size())));
  w.u32(static_cast<std::uint32_t>(crc32_z(0, compressed.data(), csize)));
  w.u64(payload.size());
  w.u64(csize);
  w.bytes().insert(w.bytes().end(), compressed.begin(), compressed.begin() + static_cast<std::ptrdiff_t>(csize));
  return std::move(w.bytes());
}

MapSnapshot decode_dsmap(std::span<const std::uint8_t> bytes, const std::string& name) {
  ByteReader r(bytes, name, ".dsmap header");
  const auto magic = r.take(kMagic.size(), "magic");
  if (!std::equal(magic.begin(), magic.end(), kMagic.begin()))
    fail(name, "not a .dsmap file (it does not start with \"DSMAP\")");
  const std::uint16_t version = r.u16("format version");
  if (version < kDsmapOldestReadable || version > kDsmapFormatVersion)
    fail(name, ".dsmap format version " + std::to_string(version) + " is not supported (this build reads versions " +
                   std::to_string(kDsmapOldestReadable) + " to " + std::to_string(kDsmapFormatVersion) +
                   (version > kDsmapFormatVersion ? "; it was written by a newer dsswarm)" : ")"));
  const std::uint32_t crc = r.u32("payload checksum");
  const std::uint32_t compressed_crc = r.u32("compressed checksum");
  const std::uint64_t payload_size = r.u64("payload size");
  const std::uint64_t compressed_size = r.u64("compressed size");
  if (compressed_size != r.remaining())
    fail(name, compressed_size > r.remaining()
                   ? "truncated: " + std::to_string(compressed_size) + " bytes of compressed map expected, " +
                         std::to_string(r.remaining()) + " present"
                   : std::to_string(r.remaining() - compressed_size) + " unexpected bytes after the compressed map");
  if (payload_size > kMaxPayloadBytes || payload_size > 1024 + kMaxExpansion * compressed_size)
    fail(name, "declared map size " + std::to_string(payload_size) + " bytes is implausible for " +
                   std::to_string(compressed_size) + " compressed bytes");
  const auto compressed = r.take(compressed_size, "compressed map");
  // Checked before decompressing: a damaged exchange is refused cheaply, and
  // no damage hides in bits the zstd decoder happens to ignore.
  if (static_cast<std::uint32_t>(crc32_z(0, compressed.data(), compressed.size())) != compressed_crc)
    fail(name, "checksum mismatch in the compressed map: the data is corrupt");
  // The frame states its own size too: both must agree before we allocate.
  const unsigned long long frame_size = ZSTD_getFrameContentSize(compressed.data(), compressed.size());
  if (frame_size == ZSTD_CONTENTSIZE_ERROR) fail(name, "compressed map is not a valid zstd frame");
  if (frame_size != payload_size)
    fail(name, "zstd frame holds " +
                   (frame_size == ZSTD_CONTENTSIZE_UNKNOWN ? std::string("an unknown number of") : std::to_string(frame_size)) +
                   " bytes, the header says " + std::to_string(payload_size));

  const auto size = static_cast<std::size_t>(payload_size);
  std::unique_ptr<std::uint8_t[]> payload(new std::uint8_t[std::max<std::size_t>(size, 1)]);
  const std::size_t got = ZSTD_decompress(payload.get(), size, compressed.data(), compressed.size());
  if (ZSTD_isError(got)) fail(name, std::string("corrupt compressed map (zstd: ") + ZSTD_getErrorName(got) + ")");
  if (got != size)
    fail(name, "compressed map holds " + std::to_string(got) + " bytes, the header says " + std::to_string(size));
  const auto actual_crc = static_cast<std::uint32_t>(crc32_z(0, payload.get(), size));
  if (actual_crc != crc) fail(name, "checksum mismatch in the decompressed map: the data is corrupt");
  return decode_payload({payload.get(), size}, version, name);
}

void write_dsmap(const std::string& path, const MapSnapshot& snapshot) {
  const std::vector<std::uint8_t> bytes = encode_dsmap(snapshot);
  write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

MapSnapshot read_dsmap(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path + ": no such .dsmap file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path + ": cannot read (" + ec.message() + ")");
  if (size > kMaxPayloadBytes) throw InputError(path + ": " + std::to_string(size) + " bytes is too large for a .dsmap file");
  std::ifstream in(path, std::ios::binary);
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())))
    throw InputError(path + ": cannot read the file");
  return decode_dsmap(bytes, path);
}

}  // namespace dsswarm
