#include "io/maps/annotate.hpp"

#include <gtest/gtest.h>

#include <set>

#include "common/errors.hpp"
#include "io/maps/font5x7.hpp"

namespace dsswarm {
namespace {

constexpr Rgb kWhite{255, 255, 255};
constexpr Rgb kBlack{0, 0, 0};

Image blank(int width, int height) {
  return {width, height, std::vector<Rgb>(static_cast<std::size_t>(width) * height, kWhite)};
}

std::size_t count(const Image& image, Rgb colour) {
  return static_cast<std::size_t>(std::count(image.pixels.begin(), image.pixels.end(), colour));
}

TEST(Font5x7, EveryPrintableCharacterHasItsOwnGlyph) {
  std::set<Glyph> seen;
  for (char c = kFirstGlyph; c <= kLastGlyph; ++c) {
    const Glyph& g = kFont5x7[static_cast<std::size_t>(c - kFirstGlyph)];
    EXPECT_TRUE(seen.insert(g).second) << "'" << c << "' looks like another character";
    const bool blank_glyph = std::all_of(g.begin(), g.end(), [](std::uint8_t row) { return row == 0; });
    EXPECT_EQ(blank_glyph, c == ' ') << "'" << c << "'";
    for (std::uint8_t row : g) EXPECT_LT(row, 0x20) << "'" << c << "' is wider than 5 pixels";
  }
}

TEST(DrawText, DrawsTheGlyphPixelsAtTheScaleAndClips) {
  Image image = blank(20, 20);
  draw_text(image, 1, 2, "L", kBlack, 2);  // 'L': the left column and the bottom row
  EXPECT_EQ(count(image, kBlack), (7u + 4u) * 4u);
  EXPECT_EQ(image.at(1, 2), kBlack);     // top of the stroke
  EXPECT_EQ(image.at(10, 15), kBlack);   // right end of the bottom row
  EXPECT_EQ(image.at(3, 2), kWhite);
  EXPECT_EQ(text_width("L", 2), 10);
  EXPECT_EQ(text_width("ab", 1), 11);
  EXPECT_EQ(text_width("", 3), 0);
  draw_text(image, -8, 15, "WW\x7f\xc3", kBlack, 3);  // off the picture and not ASCII: clipped, drawn as '?'
  EXPECT_THROW(draw_text(image, 0, 0, "x", kBlack, 0), ConfigError);
}

TEST(ScaleBar, RoundLengthsThatFit) {
  EXPECT_DOUBLE_EQ(scale_bar_metres(0.05, 400), 20.0);   // 20 m fits in 400 px at 5 cm
  EXPECT_DOUBLE_EQ(scale_bar_metres(0.0125, 400), 5.0);  // 5 m
  EXPECT_DOUBLE_EQ(scale_bar_metres(0.05, 50), 2.0);     // 2.5 m room: 2 m
  EXPECT_DOUBLE_EQ(scale_bar_metres(0.001, 30), 0.02);
  EXPECT_DOUBLE_EQ(scale_bar_metres(0.001, 3), 0.01);    // never shorter than a centimetre
}

TEST(WithLegend, PictureOnTopBandWithScaleBarAndEveryEntry) {
  Image picture = blank(600, 300);
  fill_rect(picture, 0, 0, 600, 300, Rgb{205, 205, 205});
  const Rgb red{230, 25, 75}, blue{0, 130, 200};
  const Image out = with_legend(picture, 0.05,
                                {{"robot1", red, LegendEntry::Mark::Line}, {"robot2", blue, LegendEntry::Mark::Ring}});
  EXPECT_EQ(out.width, 600);
  EXPECT_GT(out.height, 300);
  for (int y = 0; y < 300; y += 50) EXPECT_EQ(out.at(300, y), (Rgb{205, 205, 205}));
  Image band = out;
  band.pixels.erase(band.pixels.begin(), band.pixels.begin() + 600 * 300);
  EXPECT_GT(count(band, red), 0u);
  EXPECT_GT(count(band, blue), 0u);
  EXPECT_GT(count(band, kBlack), 0u);  // scale bar and labels

  // A picture too narrow for one entry gets a wider band; many entries wrap.
  const Image narrow = with_legend(blank(10, 10), 0.05, {{"a long robot name", red}});
  EXPECT_GT(narrow.width, 10);
  std::vector<LegendEntry> many(40, LegendEntry{"robot", red});
  EXPECT_GT(with_legend(picture, 0.05, many).height, out.height);
  EXPECT_THROW(with_legend(picture, 0.0, {}), ConfigError);
}

}  // namespace
}  // namespace dsswarm
