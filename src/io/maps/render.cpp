#include "io/maps/render.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

// map_saver's grey levels, which the shading interpolates between.
constexpr double kFreeGrey = 254.0;
constexpr double kUnknownGrey = 205.0;
constexpr double kOccupiedGrey = 0.0;

std::uint8_t grey_for(float occupancy) {
  if (!std::isfinite(occupancy)) return static_cast<std::uint8_t>(kUnknownGrey);
  const double p = std::clamp(static_cast<double>(occupancy), 0.0, 1.0);
  const double grey = p <= 0.5 ? kFreeGrey + (kUnknownGrey - kFreeGrey) * (p / 0.5)
                               : kUnknownGrey + (kOccupiedGrey - kUnknownGrey) * ((p - 0.5) / 0.5);
  return static_cast<std::uint8_t>(std::lround(grey));
}

int scale_of(const Image& image, const GridRaster& frame) {
  const int scale = frame.width > 0 ? image.width / frame.width : 0;
  if (scale < 1 || image.width != frame.width * scale || image.height != frame.height * scale) {
    throw ConfigError(fmt::format("image {}x{} was not rendered from a {}x{} raster at an integer scale",
                                  image.width, image.height, frame.width, frame.height));
  }
  if (image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height)) {
    throw ConfigError(fmt::format("image has {} pixels, expected {}x{}", image.pixels.size(), image.width,
                                  image.height));
  }
  return scale;
}

// Thick lines cost thickness² per pixel of length; wider is not a line any more.
constexpr int kMaxThickness = 64;

// Beyond this a pixel coordinate is a bug upstream; treating it like a
// non-finite point keeps the clipping arithmetic far from overflow.
constexpr double kFarAway = 1e150;

bool drawable(const Eigen::Vector2d& p) { return p.allFinite() && p.cwiseAbs().maxCoeff() < kFarAway; }

// Liang–Barsky: clips segment a→b to [lo, hi]² box; false if nothing remains.
bool clip_segment(Eigen::Vector2d& a, Eigen::Vector2d& b, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  const Eigen::Vector2d d = b - a;
  double t0 = 0.0, t1 = 1.0;
  const std::array<double, 4> p{-d.x(), d.x(), -d.y(), d.y()};
  const std::array<double, 4> q{a.x() - lo.x(), hi.x() - a.x(), a.y() - lo.y(), hi.y() - a.y()};
  for (std::size_t i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;  // parallel to this edge and outside it
      continue;
    }
    const double r = q[i] / p[i];
    if (p[i] < 0.0) {
      if (r > t1) return false;
      t0 = std::max(t0, r);
    } else {
      if (r < t0) return false;
      t1 = std::min(t1, r);
    }
  }
  const Eigen::Vector2d start = a + t0 * d;
  b = a + t1 * d;
  a = start;
  return true;
}

// A thickness×thickness square of pixels, clipped to the image.
void stamp(Image& image, int x, int y, int thickness, Rgb colour) {
  const int lo = -(thickness - 1) / 2;
  const int hi = thickness / 2;
  for (int dy = lo; dy <= hi; ++dy) {
    const int py = y + dy;
    if (py < 0 || py >= image.height) continue;
    for (int dx = lo; dx <= hi; ++dx) {
      const int px = x + dx;
      if (px >= 0 && px < image.width) image.at(px, py) = colour;
    }
  }
}

void draw_segment(Image& image, Eigen::Vector2d a, Eigen::Vector2d b, Rgb colour, int thickness) {
  // Clip to the picture plus a margin, so thick lines just outside still show their edge.
  const double margin = thickness;
  if (!clip_segment(a, b, {-margin, -margin}, {image.width + margin, image.height + margin})) return;
  int x0 = static_cast<int>(std::floor(a.x())), y0 = static_cast<int>(std::floor(a.y()));
  const int x1 = static_cast<int>(std::floor(b.x())), y1 = static_cast<int>(std::floor(b.y()));
  // Bresenham over whole pixels.
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  while (true) {
    stamp(image, x0, y0, thickness, colour);
    if (x0 == x1 && y0 == y1) break;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y0 += sy;
    }
  }
}

}  // namespace

Image render_map(const GridRaster& raster, int scale) {
  if (scale < 1) throw ConfigError(fmt::format("map picture scale must be at least 1, got {}", scale));
  if (raster.width < 0 || raster.height < 0 ||
      raster.cells.size() != static_cast<std::size_t>(raster.width) * static_cast<std::size_t>(raster.height)) {
    throw InputError(fmt::format("cannot render map: raster has {} cells, expected {}x{}", raster.cells.size(),
                                 raster.width, raster.height));
  }
  const long long width = static_cast<long long>(raster.width) * scale;
  const long long height = static_cast<long long>(raster.height) * scale;
  if (width > kMaxImageSide || height > kMaxImageSide) {
    throw ConfigError(fmt::format("map picture {}x{} cells at scale {} would be {}x{} pixels, more than {} a side",
                                  raster.width, raster.height, scale, width, height, kMaxImageSide));
  }
  Image image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.pixels.resize(static_cast<std::size_t>(width * height));
  for (int cy = 0; cy < raster.height; ++cy) {
    const int top = (raster.height - 1 - cy) * scale;  // highest y at the top
    for (int cx = 0; cx < raster.width; ++cx) {
      const std::uint8_t g = grey_for(raster.at(cx, cy).occupancy());
      const Rgb grey{g, g, g};
      for (int sy = 0; sy < scale; ++sy) {
        std::fill_n(&image.at(cx * scale, top + sy), scale, grey);
      }
    }
  }
  return image;
}

Eigen::Vector2d world_to_pixel(const Image& image, const GridRaster& frame, const Eigen::Vector2d& world) {
  const double scale = scale_of(image, frame);
  const Eigen::Vector2d cell = frame.to_cell(world);
  return {cell.x() * scale, (frame.height - cell.y()) * scale};
}

void draw_polyline(Image& image, const GridRaster& frame, const std::vector<Eigen::Vector2d>& world_points,
                   Rgb colour, int thickness) {
  if (thickness < 1 || thickness > kMaxThickness) {
    throw ConfigError(fmt::format("line thickness must be 1..{} pixels, got {}", kMaxThickness, thickness));
  }
  scale_of(image, frame);  // reject a mismatched frame even when there is nothing to draw
  std::vector<Eigen::Vector2d> pixels;
  pixels.reserve(world_points.size());
  for (const auto& w : world_points) pixels.push_back(world_to_pixel(image, frame, w));

  for (std::size_t i = 0; i < pixels.size(); ++i) {
    if (!drawable(pixels[i])) continue;
    const bool has_next = i + 1 < pixels.size() && drawable(pixels[i + 1]);
    const bool has_previous = i > 0 && drawable(pixels[i - 1]);
    if (has_next) {
      draw_segment(image, pixels[i], pixels[i + 1], colour, thickness);
    } else if (!has_previous) {
      draw_segment(image, pixels[i], pixels[i], colour, thickness);  // isolated point: a dot
    }
  }
}

void draw_marker(Image& image, const GridRaster& frame, const Eigen::Vector2d& world, Rgb colour, int radius) {
  if (radius < 0 || radius > 1000) throw ConfigError(fmt::format("marker radius must be 0..1000 pixels, got {}", radius));
  const Eigen::Vector2d centre = world_to_pixel(image, frame, world);
  fill_disc(image, centre.x(), centre.y(), radius, colour);
}

void fill_disc(Image& image, double x, double y, int radius, Rgb colour) {
  if (radius < 0 || radius > 1000) throw ConfigError(fmt::format("disc radius must be 0..1000 pixels, got {}", radius));
  if (!std::isfinite(x) || !std::isfinite(y)) return;
  // Reject far-away centres in floating point, before any conversion to int.
  if (x + radius + 1 < 0 || x - radius - 1 > image.width || y + radius + 1 < 0 || y - radius - 1 > image.height) return;
  const int cx = static_cast<int>(std::floor(x)), cy = static_cast<int>(std::floor(y));
  const int reach = radius * (radius + 1);  // r² + r rounds the disc's outline nicely
  for (int py = std::max(0, cy - radius); py <= std::min(image.height - 1, cy + radius); ++py) {
    for (int px = std::max(0, cx - radius); px <= std::min(image.width - 1, cx + radius); ++px) {
      if ((px - cx) * (px - cx) + (py - cy) * (py - cy) <= reach) image.at(px, py) = colour;
    }
  }
}

Rgb agent_colour(int index) {
  // Sasha Trubetskoy's "distinct colours", minus the greys and pastels that
  // vanish on a grey-level map.
  static constexpr std::array<Rgb, 8> kPalette{{
      {230, 25, 75},   // red
      {0, 130, 200},   // blue
      {60, 180, 75},   // green
      {245, 130, 48},  // orange
      {145, 30, 180},  // purple
      {0, 170, 170},   // teal
      {240, 50, 230},  // magenta
      {154, 99, 36},   // brown
  }};
  const int n = static_cast<int>(kPalette.size());
  return kPalette[static_cast<std::size_t>(((index % n) + n) % n)];
}

}  // namespace dsswarm
