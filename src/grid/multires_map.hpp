#pragma once
// The robot's map: the same Dempster–Shafer evidence accumulated at several
// resolutions (finest first, each level twice as coarse as the one before).
// The finest level is the map users see; the coarser ones give the matcher a
// wide, smooth basin so that it can recover from a poor prior before it
// refines on the fine level (the multi-resolution idea of Hector SLAM).
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "geometry/pose2.hpp"
#include "grid/ds_grid.hpp"
#include "grid/evidence_model.hpp"
#include "sensor/scan_points.hpp"

namespace dsswarm {

struct MapConfig {
  double resolution = 0.05;  // metres per cell of the finest level
  int levels = 3;            // 0.05 / 0.10 / 0.20 m by default
  EvidenceModel evidence;
  // Coarse levels serve only the matcher's first, rough placement. By default
  // they record where obstacles were seen (hits only, no beam traversal): a
  // wide, stable basin, and 3–4× less insertion work.
  bool free_space_on_coarse_levels = false;
  // Spread hits bilinearly over four cells on the finest level too (coarse
  // levels always do; see insert_scan).
  bool splat_fine_hits = false;
  // Fine level: consecutive returns closer than this (m) are joined into a
  // surface, and the cells between them get `surface_mass_factor` × the hit
  // mass (0 disables). Well below 1, a wall seen from one viewpoint is a row
  // of strong dots at its beams' ends; the next scan along a corridor puts its
  // side-wall returns exactly onto those dots by not moving, and with a
  // free-space margin (below) nothing ahead outweighs that: at 0.5 the demo
  // robot stuck for 15 scans where it started. 0.75 leaves no such stick.
  double surface_gap = 0.25;
  float surface_mass_factor = 0.75f;
  // ... unless the segment runs within acos(surface_max_cos) of the beam
  // direction (a depth discontinuity rather than a surface).
  double surface_max_cos = 0.95;
  // Free evidence along a beam stops this many cells short of its hit (0:
  // it runs up to the hit's cell). Range noise puts a surface's hits in the
  // cells on both sides of the cell border it lies near, and free evidence
  // running up to each hit fights the hits in the cells the surface
  // occupies: the map's walls flicker and its heading bends slowly. Measured
  // (README, "Swarm, simulated"): single robots' ATE median 0.021 → 0.013 m,
  // and every merge of the simulated swarm within 0.05 m and 0.5°.
  double free_margin_cells = 1.0;

  void validate() const;
};

class MultiResMap {
 public:
  explicit MultiResMap(const MapConfig& config = {});

  const MapConfig& config() const { return config_; }
  int levels() const { return static_cast<int>(grids_.size()); }
  const DsGrid& level(int i) const { return grids_[static_cast<std::size_t>(i)]; }
  const DsGrid& finest() const { return grids_.front(); }
  // Direct cell access for code that builds maps other than from scans
  // (loading a saved map, merging another robot's map).
  DsGrid& mutable_level(int i) { return grids_[static_cast<std::size_t>(i)]; }

  // Adds the evidence of one scan: free along each beam from the laser to the
  // hit, then occupied at the hit. `points` are in the robot base frame, as
  // produced by scan_to_points(); `laser_in_base` is the mounting offset.
  void insert_scan(const Pose2& robot_pose, const Pose2& laser_in_base, const std::vector<ScanPoint>& points);
  // The same scan into several maps of this one's configuration whose cells
  // coincide (local SLAM's local map and current submap): each gets exactly
  // what insert_scan would give it, the rays are traced once.
  static void insert_scan(std::span<MultiResMap* const> maps, const Pose2& robot_pose, const Pose2& laser_in_base,
                          const std::vector<ScanPoint>& points);

  std::size_t cells_allocated() const;
  std::size_t memory_bytes() const;

 private:
  MapConfig config_;
  std::vector<DsGrid> grids_;
  // The stored cell a beam's pass leaves as it is (free at its cap, nothing
  // occupied), where passes alone lead: open space, crossed by most beams.
  // Insertion skips it; the result is the same to the bit.
  PackedMass pass_fixed_point_;
  // The pass's result for each free mass of a cell with no occupied mass.
  std::shared_ptr<const std::vector<std::uint16_t>> passed_free_;
};

}  // namespace dsswarm
