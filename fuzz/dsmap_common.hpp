#pragma once
// Shared by the two .dsmap targets: tiny snapshots to seed them, and the
// check that whatever decodes encodes and decodes again.
#include <memory>
#include <utility>
#include <vector>

#include "fuzz_support.hpp"
#include "io/maps/dsmap.hpp"

namespace dsswarm::fuzz {

// A few beams seen from the middle of one 64×64 tile of a one-level map:
// the smallest map that stores a tile. Plus snapshots with no layer and with
// an empty three-level layer.
inline std::vector<std::pair<std::string, MapSnapshot>> dsmap_seed_snapshots() {
  MapConfig one_level;
  one_level.levels = 1;
  auto tiny = std::make_shared<MultiResMap>(one_level);
  const Pose2 middle(1.6, 1.6, 0.3);
  tiny->insert_scan(middle, Pose2(), {{0.5F, 0.0F, 1.0F}, {0.4F, 0.3F, 1.0F}, {0.0F, -0.6F, 1.0F}});
  MapSnapshot one_tile{"alpha", {{"alpha", 3, Pose2(), 0, tiny, {}}}};
  MapSnapshot no_layer{"bravo", {}};
  MapSnapshot empty_layers{"charlie",
                           {{"charlie", 0, Pose2(), 0, std::make_shared<MultiResMap>(MapConfig{}), {}},
                            {"delta", 9, Pose2(2.5, -1.0, 0.5), 1, std::make_shared<MultiResMap>(MapConfig{}), {}}}};
  // A robot with loop closure on: the growing submap as the map, a finished one as a piece.
  MapSnapshot with_piece{"echo",
                         {{"echo", 5, Pose2(), 0, std::make_shared<MultiResMap>(one_level),
                           {{2, Pose2(0.5, -0.25, 0.1), std::make_shared<const FrozenMap>(*tiny)}}}}};
  return {{"one-tile", std::move(one_tile)},
          {"no-layer", std::move(no_layer)},
          {"empty-layers", std::move(empty_layers)},
          {"with-piece", std::move(with_piece)}};
}

inline void check_round_trip(const MapSnapshot& snapshot, const std::string& name) {
  try {
    decode_dsmap(encode_dsmap(snapshot), name);
  } catch (const std::exception& e) {
    fail(std::string("a decoded map does not encode and decode again: ") + e.what());
  }
}

}  // namespace dsswarm::fuzz
