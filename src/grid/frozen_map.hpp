#pragma once
// A map that will not change again, kept small: a finished submap. Only the
// 16×16-cell blocks that hold evidence are kept (a submap's evidence fills a
// quarter of the 64×64 tiles a live grid allocates for it), each cell's
// occupied and free masses as one byte each on a square-root scale
// (m = (q/255)²: one beam's free mass, 0.04, is kept within 1%, a hit within
// 0.3%), and the bytes of each level zstd-compressed (as the .dsmap format
// does; most cells of a block are alike). Thawing gives back a MultiResMap
// with those masses.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/pose2.hpp"
#include "grid/multires_map.hpp"

namespace dsswarm {

class FrozenMap {
 public:
  FrozenMap() = default;
  explicit FrozenMap(const MultiResMap& map);

  // The map again (masses as stored), with `config`: its resolution must be
  // the frozen map's; with fewer levels, only the finest ones are thawed;
  // with a region, only the blocks of the finest level that overlap the
  // cells [region_min, region_max) (and coarser levels' blocks over the same area).
  MultiResMap thaw(const MapConfig& config) const;
  MultiResMap thaw(const MapConfig& config, CellIndex region_min, CellIndex region_max) const;
  std::size_t memory_bytes() const;
  // Whether any cell holds evidence (a block is kept only when one does).
  bool holds_evidence() const { return !levels_.empty() && levels_.front().blocks > 0; }
  // The finest level's bounding box of allocated tiles, as DsGrid::bounds gave it.
  void bounds(CellIndex& min, CellIndex& max) const {
    min = bounds_min_;
    max = bounds_max_;
  }

  static constexpr int kBlock = 16;

 private:
  struct Level {
    std::size_t blocks = 0;
    std::size_t raw_bytes = 0;
    std::vector<std::uint8_t> compressed;  // block origins, then all occupied bytes, then all free bytes
  };
  MultiResMap thaw(const MapConfig& config, const CellIndex* region_min, const CellIndex* region_max) const;

  std::vector<Level> levels_;
  CellIndex bounds_min_, bounds_max_;
};

// A finished submap where its cells lie in some robot's map frame: a piece
// of that robot's map, as its snapshots carry it and others hold it.
struct MapPiece {
  int id = 0;                            // the submap's id on the robot that made it
  Pose2 pose;                            // where its cells lie in that robot's frame
  std::shared_ptr<const FrozenMap> map;  // its evidence (finished: never changes)
};

}  // namespace dsswarm
