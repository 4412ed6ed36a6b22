#pragma once
// Pictures a person looks at: the map in grey levels, with trajectories and
// markers drawn over it, saved as PNG.
#include <algorithm>
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "grid/grid_raster.hpp"

namespace dsswarm {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

struct Image {
  int width = 0;
  int height = 0;
  std::vector<Rgb> pixels;  // row-major; row 0 = TOP of the picture

  Rgb& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const Rgb& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

// Largest picture side we produce; bigger requests are a ConfigError rather
// than gigabytes of allocation.
inline constexpr int kMaxImageSide = 20000;

// Grey-level map like a map_saver map but shaded: occupancy 0 → 254 (white),
// 0.5 (unknown) → 205, 1 → 0 (black), linear in between. Each cell becomes
// scale×scale pixels; the picture's top row is the map's highest y.
// Throws ConfigError if scale < 1 or the picture would exceed kMaxImageSide,
// InputError if the raster's cells do not match its size.
Image render_map(const GridRaster& raster, int scale = 1);

// The largest whole scale (1..4) that keeps a picture of `raster` within
// about 1600 pixels a side: cells stay visible on small maps.
inline int fitting_scale(const GridRaster& raster) {
  return std::max(1, std::min(4, 1600 / std::max({raster.width, raster.height, 1})));
}

// Continuous pixel coordinates of a world point in an image rendered from
// `frame` (x right, y down; pixel (i, j) covers [i, i+1) × [j, j+1)). The scale
// is image.width / frame.width; ConfigError if the image does not match the
// frame at an integer scale.
Eigen::Vector2d world_to_pixel(const Image& image, const GridRaster& frame, const Eigen::Vector2d& world);

// Draws the polyline through `world_points`, clipped to the picture (points far
// outside or non-finite are fine: non-finite points break the line). A single
// point draws a dot. thickness is in pixels (1..64, else ConfigError).
void draw_polyline(Image& image, const GridRaster& frame, const std::vector<Eigen::Vector2d>& world_points,
                   Rgb colour, int thickness = 1);

// A filled disc of `radius` pixels (0 = one pixel) centred on `world`, clipped.
// radius must be 0..1000 (else ConfigError).
void draw_marker(Image& image, const GridRaster& frame, const Eigen::Vector2d& world, Rgb colour, int radius);

// draw_marker in pixel coordinates: a filled disc centred on (x, y), clipped.
void fill_disc(Image& image, double x, double y, int radius, Rgb colour);

// Eight colours that stay distinct from each other and from the grey map;
// any index (negative too) wraps around the palette.
Rgb agent_colour(int index);

// 8-bit RGB PNG, written atomically. InputError (naming the file) for an empty
// or inconsistent image, a libpng failure, or a file that cannot be written.
void write_png(const std::filesystem::path& path, const Image& image);

// The bytes write_png writes; errors name `path`.
std::string encode_png(const std::filesystem::path& path, const Image& image);

}  // namespace dsswarm
