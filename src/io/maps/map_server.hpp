#pragma once
// ROS map_server maps: a PGM picture plus a YAML description, written the way
// map_saver writes them and read the way map_server loads them, so our maps
// drop straight into a ROS navigation stack.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "grid/grid_raster.hpp"
#include "io/atomic_file.hpp"

namespace dsswarm {

struct MapServerOptions {
  double occupied_thresh = 0.65;  // occupancy above this is occupied
  double free_thresh = 0.196;     // occupancy below this is free
  bool negate = false;            // true: white means occupied in the picture
};

// The ROS OccupancyGrid value of a cell as a map written with `options` reads
// back in map_server (trinary): p = cell.occupancy() > occupied_thresh → 100,
// p < free_thresh → 0, else −1 (unknown). The live /map uses it too, so it
// shows what map_server would serve.
inline std::int8_t occupancy_grid_value(const DsMass& cell, const MapServerOptions& options) {
  const double p = cell.occupancy();
  if (p > options.occupied_thresh) return 100;
  if (p < options.free_thresh) return 0;
  return -1;
}

// Throws ConfigError for thresholds that map_server could not read back
// (need 1/255 < free_thresh < occupied_thresh < 1).
void check_map_server_options(const MapServerOptions& options);

// Writes NAME.pgm next to `yaml_path` (= NAME.yaml), then the YAML that points
// at it. Cells are classified by p = cell.occupancy(): p > occupied_thresh is
// occupied (pixel 0), p < free_thresh is free (254), anything else unknown (205)
// — map_saver's values, which map_server reads back as the same classes.
// With negate the pixels are inverted (255 − value) and the YAML says so.
// Throws ConfigError for thresholds that check_map_server_options rejects and
// InputError for an empty or inconsistent raster or a file that cannot be written.
void write_map_server(const std::filesystem::path& yaml_path, const GridRaster& raster,
                      const MapServerOptions& options = {});

// The same two files added to `files` (image first), to be written with the
// command's other outputs. The same errors, before anything is written.
void add_map_server(OutputFiles& files, const std::filesystem::path& yaml_path, const GridRaster& raster,
                    const MapServerOptions& options = {});

struct LoadedMap {
  // Masses reconstructed from the classes: occupied → {1, 0}, free → {0, 1},
  // unknown → {0, 0}. In "scale" mode an in-between value v (1..99) becomes the
  // mass whose occupancy() is v/100.
  GridRaster raster;
  // ROS OccupancyGrid values: 100 occupied, 0 free, −1 unknown (1..99 only in
  // "scale" mode); row 0 = lowest y, like the raster.
  std::vector<std::int8_t> occupancy;
  MapServerOptions options;  // thresholds and negate as the YAML gave them
};

// Loads a map as ROS1 map_server does: p = (255 − v)/255 for a pixel value v
// (p = v/255 with negate); trinary mode (the default): p > occupied_thresh →
// 100, p < free_thresh → 0, else −1. "scale" mode is also accepted; "raw" is
// not (its values do not fit an occupancy grid). `image` is relative to the
// YAML's folder or absolute, and must be a P5 or P2 PGM. The origin's yaw
// must be 0 (a GridRaster is axis-aligned).
// Every problem is an InputError naming the file and the key or line.
LoadedMap read_map_server(const std::filesystem::path& yaml_path);

}  // namespace dsswarm
