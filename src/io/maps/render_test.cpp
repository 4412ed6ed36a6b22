#include "io/maps/render.hpp"

#include <gtest/gtest.h>
#include <png.h>

#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(DSSWARM_TEST_TMP) / "maps_render" / info->name();
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

GridRaster vacuous_raster(int width, int height, double resolution = 1.0) {
  GridRaster r;
  r.width = width;
  r.height = height;
  r.resolution = resolution;
  r.origin = {0.0, 0.0};
  r.cells.assign(static_cast<std::size_t>(width) * height, DsMass::vacuous());
  return r;
}

constexpr Rgb kRed{255, 0, 0};
constexpr Rgb kUnknown{205, 205, 205};

std::set<std::pair<int, int>> pixels_with(const Image& image, Rgb colour) {
  std::set<std::pair<int, int>> found;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (image.at(x, y) == colour) found.insert({x, y});
    }
  }
  return found;
}

TEST(RenderMap, GreyLevelsAndRowFlip) {
  GridRaster r = vacuous_raster(3, 2);
  r.cells[0] = {1.0f, 0.0f};      // (0, 0): occupied, bottom-left
  r.cells[5] = {0.0f, 1.0f};      // (2, 1): free, top-right
  r.cells[1] = {0.5f, 0.0f};      // (1, 0): occupancy 0.75
  r.cells[3] = {0.0f, 0.5f};      // (0, 1): occupancy 0.25
  const Image image = render_map(r, 2);
  ASSERT_EQ(image.width, 6);
  ASSERT_EQ(image.height, 4);
  ASSERT_EQ(image.pixels.size(), 24u);
  for (int dy = 0; dy < 2; ++dy) {
    for (int dx = 0; dx < 2; ++dx) {
      EXPECT_EQ(image.at(0 + dx, 2 + dy), (Rgb{0, 0, 0}));        // occupied at the bottom-left
      EXPECT_EQ(image.at(4 + dx, 0 + dy), (Rgb{254, 254, 254}));  // free at the top-right
      EXPECT_EQ(image.at(2 + dx, 2 + dy), (Rgb{103, 103, 103}));  // halfway from 205 to 0
      EXPECT_EQ(image.at(0 + dx, 0 + dy), (Rgb{230, 230, 230}));  // halfway from 254 to 205 (229.5)
      EXPECT_EQ(image.at(2 + dx, 0 + dy), kUnknown);
    }
  }
}

TEST(RenderMap, RefusesBadScaleAndAbsurdSizes) {
  const GridRaster r = vacuous_raster(4, 3);
  EXPECT_THROW(render_map(r, 0), ConfigError);
  EXPECT_THROW(render_map(r, 10000), ConfigError);
  EXPECT_THROW(render_map(vacuous_raster(kMaxImageSide + 1, 1)), ConfigError);
  EXPECT_NO_THROW(render_map(vacuous_raster(kMaxImageSide, 1)));
  GridRaster broken = r;
  broken.cells.pop_back();
  EXPECT_THROW(render_map(broken), InputError);
}

struct DecodedPng {
  int width = 0, height = 0;
  std::vector<Rgb> pixels;
};

DecodedPng read_png(const fs::path& path) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) {
    ADD_FAILURE() << "libpng cannot read " << path << ": " << png.message;
    return {};
  }
  png.format = PNG_FORMAT_RGB;
  DecodedPng out;
  out.width = static_cast<int>(png.width);
  out.height = static_cast<int>(png.height);
  out.pixels.resize(static_cast<std::size_t>(out.width) * out.height);
  if (!png_image_finish_read(&png, nullptr, out.pixels.data(), 0, nullptr)) {
    ADD_FAILURE() << "libpng cannot decode " << path << ": " << png.message;
  }
  return out;
}

TEST(WritePng, IsAnEightBitRgbPngWithTheSamePixels) {
  const fs::path dir = fresh_dir();
  GridRaster r = vacuous_raster(5, 4);
  r.cells[0] = {1.0f, 0.0f};
  r.cells[19] = {0.0f, 1.0f};
  Image image = render_map(r, 3);
  image.at(7, 1) = kRed;
  image.at(14, 11) = agent_colour(1);
  write_png(dir / "map.png", image);

  std::ifstream in(dir / "map.png", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 26u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  EXPECT_EQ(bytes[24], 8);                  // bit depth
  EXPECT_EQ(bytes[25], PNG_COLOR_TYPE_RGB);  // colour type

  const DecodedPng decoded = read_png(dir / "map.png");
  ASSERT_EQ(decoded.width, 15);
  ASSERT_EQ(decoded.height, 12);
  EXPECT_EQ(decoded.pixels, image.pixels);
  EXPECT_EQ(decoded.pixels[1 * 15 + 7], kRed);
  EXPECT_EQ(decoded.pixels[11 * 15 + 0], (Rgb{0, 0, 0}));      // cell (0, 0) at the bottom-left
  EXPECT_EQ(decoded.pixels[0 * 15 + 14], (Rgb{254, 254, 254}));  // cell (4, 3) at the top-right
}

TEST(WritePng, BadImagesAndMissingFoldersAreInputErrors) {
  const fs::path dir = fresh_dir();
  EXPECT_THROW(write_png(dir / "empty.png", Image{}), InputError);
  Image inconsistent = render_map(vacuous_raster(2, 2));
  inconsistent.pixels.pop_back();
  EXPECT_THROW(write_png(dir / "bad.png", inconsistent), InputError);
  EXPECT_THROW(write_png(dir / "no_such_dir" / "x.png", render_map(vacuous_raster(2, 2))), InputError);
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(DrawPolyline, HorizontalLineCrossesTheWholePictureAndClips) {
  const GridRaster frame = vacuous_raster(10, 10);
  Image image = render_map(frame);
  draw_polyline(image, frame, {{-100.0, 4.5}, {100.0, 4.5}}, kRed);
  // World y = 4.5 is cell row 4, which is picture row 10 − 1 − 4 = 5.
  std::set<std::pair<int, int>> expected;
  for (int x = 0; x < 10; ++x) expected.insert({x, 5});
  EXPECT_EQ(pixels_with(image, kRed), expected);
}

TEST(DrawPolyline, DiagonalTouchesOnePixelPerColumn) {
  const GridRaster frame = vacuous_raster(10, 10, 0.5);
  Image image = render_map(frame, 2);  // 20 × 20 pixels, 4 pixels per metre
  draw_polyline(image, frame, {{0.1, 0.1}, {4.9, 4.9}}, kRed);
  std::set<std::pair<int, int>> expected;
  for (int i = 0; i < 20; ++i) expected.insert({i, 19 - i});
  EXPECT_EQ(pixels_with(image, kRed), expected);
}

TEST(DrawPolyline, ThicknessWidensTheLine) {
  const GridRaster frame = vacuous_raster(10, 10);
  Image image = render_map(frame);
  draw_polyline(image, frame, {{2.5, -5.0}, {2.5, 50.0}}, kRed, 3);
  std::set<std::pair<int, int>> expected;
  for (int y = 0; y < 10; ++y) {
    for (int x = 1; x <= 3; ++x) expected.insert({x, y});
  }
  EXPECT_EQ(pixels_with(image, kRed), expected);
  EXPECT_THROW(draw_polyline(image, frame, {{0, 0}}, kRed, 0), ConfigError);
}

TEST(DrawPolyline, OutsideHugeAndNonFinitePointsDrawNothingAndDoNotCrash) {
  const GridRaster frame = vacuous_raster(10, 10);
  Image image = render_map(frame);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  draw_polyline(image, frame, {{-5.0, -5.0}, {-5.0, 50.0}, {50.0, 50.0}}, kRed);  // passes around the picture
  draw_polyline(image, frame, {{1e300, 1e300}, {-1e300, -1e300}, {nan, 0.0}, {inf, -inf}}, kRed);
  draw_polyline(image, frame, {}, kRed);
  EXPECT_TRUE(pixels_with(image, kRed).empty());
  // A NaN breaks the line: the points on either side become dots.
  draw_polyline(image, frame, {{1.5, 1.5}, {nan, nan}, {7.5, 1.5}}, kRed);
  EXPECT_EQ(pixels_with(image, kRed), (std::set<std::pair<int, int>>{{1, 8}, {7, 8}}));
}

TEST(DrawPolyline, RefusesAnImageFromAnotherFrame) {
  Image image = render_map(vacuous_raster(10, 10));
  EXPECT_THROW(draw_polyline(image, vacuous_raster(3, 3), {{0, 0}, {1, 1}}, kRed), ConfigError);
  EXPECT_THROW(draw_marker(image, vacuous_raster(10, 9), {0, 0}, kRed, 1), ConfigError);
}

TEST(DrawMarker, FilledDiscClippedAtTheEdge) {
  const GridRaster frame = vacuous_raster(10, 10);
  Image image = render_map(frame);
  draw_marker(image, frame, {5.5, 4.5}, kRed, 0);
  EXPECT_EQ(pixels_with(image, kRed), (std::set<std::pair<int, int>>{{5, 5}}));

  image = render_map(frame);
  draw_marker(image, frame, {5.5, 4.5}, kRed, 2);
  const auto disc = pixels_with(image, kRed);
  EXPECT_EQ(disc.size(), 21u);  // 5×5 square minus its 4 corners
  EXPECT_TRUE(disc.count({5, 3}) && disc.count({3, 5}) && disc.count({6, 6}));
  EXPECT_FALSE(disc.count({3, 3}) || disc.count({7, 7}));

  image = render_map(frame);
  draw_marker(image, frame, {0.5, 0.5}, kRed, 1);  // bottom-left corner: only a quarter shows
  EXPECT_EQ(pixels_with(image, kRed), (std::set<std::pair<int, int>>{{0, 9}, {1, 9}, {0, 8}, {1, 8}}));

  image = render_map(frame);
  draw_marker(image, frame, {1e200, -1e200}, kRed, 3);
  draw_marker(image, frame, {std::numeric_limits<double>::quiet_NaN(), 0.0}, kRed, 3);
  EXPECT_TRUE(pixels_with(image, kRed).empty());
  EXPECT_THROW(draw_marker(image, frame, {0, 0}, kRed, -1), ConfigError);
}

TEST(AgentColour, EightDistinctNonGreyColoursThatWrap) {
  std::set<std::tuple<int, int, int>> seen;
  for (int i = 0; i < 8; ++i) {
    const Rgb c = agent_colour(i);
    seen.insert({c.r, c.g, c.b});
    EXPECT_FALSE(c.r == c.g && c.g == c.b) << "colour " << i << " is grey";
  }
  EXPECT_EQ(seen.size(), 8u);
  EXPECT_EQ(agent_colour(8), agent_colour(0));
  EXPECT_EQ(agent_colour(-1), agent_colour(7));
  EXPECT_EQ(agent_colour(std::numeric_limits<int>::min()), agent_colour(std::numeric_limits<int>::min() % 8 + 8));
}

}  // namespace
}  // namespace dsswarm
