#include "io/maps/annotate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

#include "common/errors.hpp"
#include "io/maps/font5x7.hpp"

namespace dsswarm {
namespace {

constexpr int kAdvance = kGlyphWidth + 1;  // one blank column between characters
constexpr int kMaxTextScale = 16;
constexpr Rgb kInk{0, 0, 0};
constexpr Rgb kPaper{255, 255, 255};

// One item of the band: its size, and how to draw it at a place.
struct BandItem {
  int width = 0;
  std::function<void(Image&, int x, int y)> draw;  // (x, y) = top-left of the row
};

BandItem scale_bar_item(double metres_per_pixel, int picture_width, int s) {
  const double metres = scale_bar_metres(metres_per_pixel, std::max(1, picture_width / 4));
  const int length = std::max(1, static_cast<int>(std::lround(metres / metres_per_pixel)));
  const std::string label = fmt::format("{} m", metres);
  BandItem item;
  item.width = length + 3 * s + text_width(label, s);
  item.draw = [=](Image& image, int x, int y) {
    const int mid = y + text_height(s) / 2;
    fill_rect(image, x, mid - s / 2, length, s, kInk);
    fill_rect(image, x, mid - 2 * s, s, 4 * s, kInk);  // end ticks
    fill_rect(image, x + length - s, mid - 2 * s, s, 4 * s, kInk);
    draw_text(image, x + length + 3 * s, y, label, kInk, s);
  };
  return item;
}

BandItem legend_item(const LegendEntry& e, int s) {
  return {legend_entry_width(e, s), [=](Image& image, int x, int y) { draw_legend_entry(image, x, y, e, s); }};
}

// Calls pixel(col, row) for every inked font pixel of `text` (col along the text).
template <class Pixel>
void for_each_ink(std::string_view text, int scale, Pixel pixel) {
  if (scale < 1 || scale > kMaxTextScale)
    throw ConfigError(fmt::format("text scale must be 1..{}, got {}", kMaxTextScale, scale));
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i] >= kFirstGlyph && text[i] <= kLastGlyph ? text[i] : '?';
    const Glyph& glyph = kFont5x7[static_cast<std::size_t>(c - kFirstGlyph)];
    const int left = static_cast<int>(i) * kAdvance;
    for (int row = 0; row < kGlyphHeight; ++row)
      for (int col = 0; col < kGlyphWidth; ++col)
        if (glyph[static_cast<std::size_t>(row)] & (0x10 >> col)) pixel(left + col, row);
  }
}

}  // namespace

int text_width(std::string_view text, int scale) {
  return text.empty() ? 0 : (static_cast<int>(text.size()) * kAdvance - 1) * scale;
}

void draw_text(Image& image, int x, int y, std::string_view text, Rgb colour, int scale) {
  for_each_ink(text, scale, [&](int col, int row) {
    fill_rect(image, x + col * scale, y + row * scale, scale, scale, colour);
  });
}

void draw_text_up(Image& image, int x, int y, std::string_view text, Rgb colour, int scale) {
  for_each_ink(text, scale, [&](int col, int row) {
    fill_rect(image, x + row * scale, y - (col + 1) * scale, scale, scale, colour);
  });
}

int legend_entry_width(const LegendEntry& e, int s) { return 8 * s + 3 * s + text_width(e.label, s); }

int draw_legend_entry(Image& image, int x, int y, const LegendEntry& e, int s) {
  const int swatch = 8 * s;
  const int mid = y + text_height(s) / 2;
  const double cx = x + swatch / 2.0, cy = mid + 0.5;
  switch (e.mark) {
    case LegendEntry::Mark::Line: fill_rect(image, x, mid - s, swatch, 2 * s, e.colour); break;
    case LegendEntry::Mark::Disc: fill_disc(image, cx, cy, 2 * s, e.colour); break;
    case LegendEntry::Mark::Ring:
      fill_disc(image, cx, cy, 2 * s, e.colour);
      fill_disc(image, cx, cy, s, kPaper);
      break;
  }
  draw_text(image, x + swatch + 3 * s, y, e.label, kInk, s);
  return legend_entry_width(e, s);
}

void fill_rect(Image& image, int x, int y, int width, int height, Rgb colour) {
  const int x0 = std::max(0, x), x1 = std::min(image.width, x + width);
  const int y0 = std::max(0, y), y1 = std::min(image.height, y + height);
  for (int py = y0; py < y1; ++py)
    for (int px = x0; px < x1; ++px) image.at(px, py) = colour;
}

void draw_path(Image& image, const GridRaster& frame, const std::vector<Eigen::Vector2d>& world_points, Rgb colour) {
  const int scale = frame.width > 0 ? image.width / frame.width : 1;
  const int thickness = std::max(3, scale);
  draw_polyline(image, frame, world_points, kPaper, thickness + 2);
  draw_polyline(image, frame, world_points, colour, thickness);
}

void draw_ringed_marker(Image& image, const GridRaster& frame, const Eigen::Vector2d& world, Rgb colour, int radius) {
  draw_marker(image, frame, world, kPaper, radius + 2);
  draw_marker(image, frame, world, colour, radius);
}

int label_scale(int width) { return std::clamp(width / 250, 2, 4); }

double scale_bar_metres(double metres_per_pixel, int max_pixels) {
  const double longest = metres_per_pixel * max_pixels;
  double best = 0.01;
  for (double decade = 0.01; decade <= longest; decade *= 10.0)
    for (double step : {1.0, 2.0, 5.0})
      if (step * decade <= longest * (1.0 + 1e-9)) best = std::round(step * decade * 100.0) / 100.0;
  return best;
}

Image with_legend(const Image& picture, double metres_per_pixel, const std::vector<LegendEntry>& legend) {
  if (!(metres_per_pixel > 0.0) || !std::isfinite(metres_per_pixel))
    throw ConfigError(fmt::format("scale bar: metres per pixel must be positive, got {}", metres_per_pixel));
  const int s = label_scale(picture.width);
  const int pad = 4 * s, row_height = text_height(s) + pad;
  std::vector<BandItem> items{scale_bar_item(metres_per_pixel, picture.width, s)};
  for (const LegendEntry& e : legend) items.push_back(legend_item(e, s));
  int width = picture.width;
  for (const BandItem& item : items) width = std::max(width, item.width + 2 * pad);
  // Rows: items left to right, a new row when the next would not fit.
  std::vector<std::pair<int, int>> at;  // per item: x, row
  int x = pad, row = 0;
  for (const BandItem& item : items) {
    if (x > pad && x + item.width > width - pad) x = pad, ++row;
    at.emplace_back(x, row);
    x += item.width + 3 * pad;
  }
  Image out{width, picture.height + pad + (row + 1) * row_height, {}};
  out.pixels.assign(static_cast<std::size_t>(out.width) * out.height, kPaper);
  for (int py = 0; py < picture.height; ++py)
    std::copy_n(&picture.at(0, py), picture.width, &out.at(0, py));
  for (std::size_t i = 0; i < items.size(); ++i)
    items[i].draw(out, at[i].first, picture.height + pad + at[i].second * row_height);
  return out;
}

}  // namespace dsswarm
