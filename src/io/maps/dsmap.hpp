#pragma once
// The .dsmap binary map format: a MapSnapshot (one or more Dempster–Shafer
// multi-resolution map layers with their provenance), used both for files
// (`dsswarm run --save-map / --load-map`) and for the bytes robots exchange
// at an encounter.
//
// Layout (all integers little-endian):
//   "DSMAP"  u16 format version (2)  u32 CRC-32 of the payload
//   u32 CRC-32 of the compressed bytes  u64 payload bytes
//   u64 compressed bytes  <zstd frame of the payload>
// Payload:
//   f64 resolution  u8 levels  f32 hit_occupied  f32 pass_free  f32 min_unknown
//   str sender  u32 layer count, then per layer:
//     str origin  u64 version  f64 x  f64 y  f64 theta  i32 hops  <levels>
//     u32 piece count, then per piece (a finished submap, MapLayer::pieces):
//       i32 id  f64 x  f64 y  f64 theta  <levels>
//   <levels>: u8 levels, then per level: u32 tiles, tiles × (i32 tile_x,
//             i32 tile_y) in tile units, then every tile's 64×64 occupied
//             masses, then every tile's free masses (planes: like values sit
//             together and compress better), each mass as u16 =
//             round(mass × 65535), rows of increasing y, x fastest.
//   (str = u32 byte length + UTF-8 bytes)
// Version 1 (before submaps) is version 2 without the piece count; it is
// still read. A piece's masses are its frozen ones (frozen_map.hpp).
// Only tiles holding a non-vacuous cell are stored. Free masses are clamped
// so that free ≤ 1 − occupied still holds after dequantization.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "swarm/map_snapshot.hpp"

namespace dsswarm {

inline constexpr std::uint16_t kDsmapFormatVersion = 2;
inline constexpr std::uint16_t kDsmapOldestReadable = 1;

// Throws std::invalid_argument when a layer has no map or its resolution /
// level count differs from layer 0's (one header describes every layer). The
// evidence model stored is layer 0's. `format_version` 1 (no pieces) is for
// tests of old files.
std::vector<std::uint8_t> encode_dsmap(const MapSnapshot& snapshot, std::uint16_t format_version = kDsmapFormatVersion);

// Throws InputError naming `name_for_errors` and what is wrong on any
// malformed input; never allocates more than a bounded multiple of the input.
// The decoded maps carry the file's resolution, levels and evidence model
// (the other MapConfig fields take their defaults).
MapSnapshot decode_dsmap(std::span<const std::uint8_t> bytes, const std::string& name_for_errors);

// File versions (written atomically). read_dsmap's errors name `path`.
void write_dsmap(const std::string& path, const MapSnapshot& snapshot);
MapSnapshot read_dsmap(const std::string& path);

}  // namespace dsswarm
