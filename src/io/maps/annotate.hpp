#pragma once
// What makes a picture readable without its caption: text labels in the
// built-in 5×7 font (font5x7.hpp), and a white band under a map picture with
// a labelled scale bar and a legend.
#include <string>
#include <string_view>
#include <vector>

#include "io/maps/render.hpp"

namespace dsswarm {

// Each font pixel becomes scale×scale pixels; a character advances 6×scale.
int text_width(std::string_view text, int scale);
inline int text_height(int scale) { return 7 * scale; }

// `text` with its top-left corner at pixel (x, y), clipped to the image.
// Characters outside ASCII 32..126 are drawn as '?'. scale must be 1..16.
void draw_text(Image& image, int x, int y, std::string_view text, Rgb colour, int scale = 1);

// The same turned a quarter left, reading upwards (a y-axis label): the
// first character's bottom-left corner at pixel (x, y).
void draw_text_up(Image& image, int x, int y, std::string_view text, Rgb colour, int scale = 1);

// Filled rectangle, clipped to the image.
void fill_rect(Image& image, int x, int y, int width, int height, Rgb colour);

// A label size that reads well on a picture `width` pixels wide (2..4).
int label_scale(int width);

// The scale bar's length: the largest 1, 2 or 5 × 10^k metres (k >= -2)
// that is at most `max_pixels` long; 0.01 m if even that is longer.
double scale_bar_metres(double metres_per_pixel, int max_pixels);

// A path a person can follow on a map picture: `colour` over a white halo
// (it stands out of walls and of other paths), 3 pixels wide or one cell at
// the picture's scale if that is wider.
void draw_path(Image& image, const GridRaster& frame, const std::vector<Eigen::Vector2d>& world_points, Rgb colour);

// A marker that shows on a path of its own colour: a disc inside a white ring.
void draw_ringed_marker(Image& image, const GridRaster& frame, const Eigen::Vector2d& world, Rgb colour, int radius);

struct LegendEntry {
  enum class Mark { Line, Disc, Ring };  // a path, a filled marker, a ring marker
  std::string label;
  Rgb colour;
  Mark mark = Mark::Line;
};

// One legend entry (mark, then label) with its top-left corner at (x, y),
// text at `scale`; returns its width in pixels.
int draw_legend_entry(Image& image, int x, int y, const LegendEntry& entry, int scale);
int legend_entry_width(const LegendEntry& entry, int scale);

// `picture` above a white band that holds a scale bar (`metres_per_pixel` of
// the picture) and the legend entries, left to right, wrapped to the width
// (the band is widened for a picture too narrow for one entry).
Image with_legend(const Image& picture, double metres_per_pixel, const std::vector<LegendEntry>& legend);

}  // namespace dsswarm
