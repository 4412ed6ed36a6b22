#include "io/maps/map_server.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>
#include <string>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(DSSWARM_TEST_TMP) / "maps_map_server" / info->name();
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void put(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

std::size_t index(int width, int cx, int cy) { return static_cast<std::size_t>(cy) * width + cx; }

// 4×3 cells: one clearly occupied, one clearly free, two that lean but stay
// inside the unknown band, the rest vacuous.
GridRaster small_raster() {
  GridRaster r;
  r.width = 4;
  r.height = 3;
  r.resolution = 0.5;
  r.origin = {-1.0, 2.0};
  r.cells.assign(12, DsMass::vacuous());
  r.cells[index(4, 1, 0)] = {0.9f, 0.0f};  // occupancy 0.95 -> occupied
  r.cells[index(4, 2, 2)] = {0.0f, 0.8f};  // occupancy 0.10 -> free
  r.cells[index(4, 3, 1)] = {0.2f, 0.0f};  // occupancy 0.60 -> unknown
  r.cells[index(4, 0, 1)] = {0.0f, 0.5f};  // occupancy 0.25 -> unknown
  return r;
}

std::string pgm_bytes(const std::string& header, const std::vector<int>& values) {
  std::string s = header;
  for (int v : values) s.push_back(static_cast<char>(static_cast<unsigned char>(v)));
  return s;
}

const char* kMapYaml =
    "image: m.pgm\nresolution: 0.05\norigin: [-10.0, -5.0, 0.0]\nnegate: 0\n"
    "occupied_thresh: 0.65\nfree_thresh: 0.196\n";

TEST(MapServerWrite, PgmBytesAreMapSaversWithRowsFlipped) {
  const fs::path dir = fresh_dir();
  write_map_server(dir / "m.yaml", small_raster());
  // Top picture row is the highest y (cy = 2).
  const std::string expected = pgm_bytes("P5\n4 3\n255\n", {205, 205, 254, 205,  // cy = 2
                                                            205, 205, 205, 205,  // cy = 1
                                                            205, 0, 205, 205});  // cy = 0
  EXPECT_EQ(slurp(dir / "m.pgm"), expected);
}

TEST(MapServerWrite, YamlHasEveryMapServerKey) {
  const fs::path dir = fresh_dir();
  write_map_server(dir / "m.yaml", small_raster());
  const YAML::Node y = YAML::LoadFile((dir / "m.yaml").string());
  EXPECT_EQ(y["image"].as<std::string>(), "m.pgm");
  EXPECT_EQ(y["mode"].as<std::string>(), "trinary");
  EXPECT_DOUBLE_EQ(y["resolution"].as<double>(), 0.5);
  ASSERT_TRUE(y["origin"].IsSequence());
  ASSERT_EQ(y["origin"].size(), 3u);
  EXPECT_DOUBLE_EQ(y["origin"][0].as<double>(), -1.0);
  EXPECT_DOUBLE_EQ(y["origin"][1].as<double>(), 2.0);
  EXPECT_DOUBLE_EQ(y["origin"][2].as<double>(), 0.0);
  EXPECT_EQ(y["negate"].as<int>(), 0);
  EXPECT_DOUBLE_EQ(y["occupied_thresh"].as<double>(), 0.65);
  EXPECT_DOUBLE_EQ(y["free_thresh"].as<double>(), 0.196);
}

// Origins are tile indices times the resolution: -224 * 0.05 is -11.200000000000001
// in binary; the file says -11.2 (a nanometre is far below any cell).
TEST(MapServerWrite, OriginIsWrittenWithoutFloatNoise) {
  const fs::path dir = fresh_dir();
  GridRaster r = small_raster();
  r.resolution = 0.05;
  r.origin = {-224 * 0.05, 3 * 0.1};
  write_map_server(dir / "m.yaml", r);
  const std::string yaml = slurp(dir / "m.yaml");
  EXPECT_NE(yaml.find("origin: [-11.2, 0.3, 0.0]\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("resolution: 0.05\n"), std::string::npos) << yaml;
}

TEST(MapServerWrite, ReadsBackAsTheSameClassesAtTheSameCells) {
  const fs::path dir = fresh_dir();
  const GridRaster original = small_raster();
  write_map_server(dir / "m.yaml", original);
  const LoadedMap map = read_map_server(dir / "m.yaml");
  ASSERT_EQ(map.raster.width, 4);
  ASSERT_EQ(map.raster.height, 3);
  EXPECT_DOUBLE_EQ(map.raster.resolution, 0.5);
  EXPECT_DOUBLE_EQ(map.raster.origin.x(), -1.0);
  EXPECT_DOUBLE_EQ(map.raster.origin.y(), 2.0);
  ASSERT_EQ(map.occupancy.size(), 12u);
  ASSERT_EQ(map.raster.cells.size(), 12u);
  for (int cy = 0; cy < 3; ++cy) {
    for (int cx = 0; cx < 4; ++cx) {
      const std::size_t i = index(4, cx, cy);
      const int expected = (cx == 1 && cy == 0) ? 100 : (cx == 2 && cy == 2) ? 0 : -1;
      EXPECT_EQ(map.occupancy[i], expected) << "cell " << cx << "," << cy;
      const DsMass m = map.raster.cells[i];
      EXPECT_FLOAT_EQ(m.occupied, expected == 100 ? 1.0f : 0.0f) << "cell " << cx << "," << cy;
      EXPECT_FLOAT_EQ(m.free, expected == 0 ? 1.0f : 0.0f) << "cell " << cx << "," << cy;
    }
  }
}

TEST(MapServerWrite, NegateInvertsPixelsAndStillReadsBack) {
  const fs::path dir = fresh_dir();
  write_map_server(dir / "n.yaml", small_raster(), {.negate = true});
  const std::string expected = pgm_bytes("P5\n4 3\n255\n", {50, 50, 1, 50, 50, 50, 50, 50, 50, 255, 50, 50});
  EXPECT_EQ(slurp(dir / "n.pgm"), expected);
  EXPECT_EQ(YAML::LoadFile((dir / "n.yaml").string())["negate"].as<int>(), 1);
  const LoadedMap map = read_map_server(dir / "n.yaml");
  EXPECT_TRUE(map.options.negate);
  EXPECT_EQ(map.occupancy[index(4, 1, 0)], 100);
  EXPECT_EQ(map.occupancy[index(4, 2, 2)], 0);
  EXPECT_EQ(map.occupancy[index(4, 0, 0)], -1);
}

TEST(MapServerWrite, OtherThresholdsPickAGreyThatStillMeansUnknown) {
  const fs::path dir = fresh_dir();
  // With free_thresh 0.3, map_saver's 205 (p = 0.196) would read back as free.
  const MapServerOptions options{.occupied_thresh = 0.9, .free_thresh = 0.3};
  write_map_server(dir / "t.yaml", small_raster(), options);
  const LoadedMap map = read_map_server(dir / "t.yaml");
  EXPECT_DOUBLE_EQ(map.options.free_thresh, 0.3);
  EXPECT_DOUBLE_EQ(map.options.occupied_thresh, 0.9);
  EXPECT_EQ(map.occupancy[index(4, 0, 0)], -1);
  EXPECT_EQ(map.occupancy[index(4, 1, 0)], 100);
  EXPECT_EQ(map.occupancy[index(4, 2, 2)], 0);
  // 0.25 is now below free_thresh: the classification follows the options.
  EXPECT_EQ(map.occupancy[index(4, 0, 1)], 0);
}

TEST(MapServerWrite, RefusesThresholdsThatCannotReadBack) {
  const fs::path dir = fresh_dir();
  EXPECT_THROW(write_map_server(dir / "a.yaml", small_raster(), {.occupied_thresh = 0.1, .free_thresh = 0.5}),
               ConfigError);
  EXPECT_THROW(write_map_server(dir / "a.yaml", small_raster(), {.occupied_thresh = 1.0}), ConfigError);
  EXPECT_THROW(write_map_server(dir / "a.yaml", small_raster(), {.free_thresh = 0.0}), ConfigError);
  EXPECT_FALSE(fs::exists(dir / "a.pgm"));
}

TEST(MapServerWrite, RefusesBrokenRastersAndMissingFolders) {
  const fs::path dir = fresh_dir();
  GridRaster empty;
  EXPECT_THROW(write_map_server(dir / "e.yaml", empty), InputError);
  GridRaster short_cells = small_raster();
  short_cells.cells.pop_back();
  EXPECT_THROW(write_map_server(dir / "s.yaml", short_cells), InputError);
  EXPECT_THROW(write_map_server(dir / "no_such_dir" / "m.yaml", small_raster()), InputError);
  EXPECT_THROW(write_map_server(dir / "m.pgm", small_raster()), InputError);
}

TEST(MapServerRead, LoadsAMapSaverFileWithCommentAndSixDecimals) {
  const fs::path dir = fresh_dir();
  put(dir / "saver.pgm", pgm_bytes("P5\n# CREATOR: map_saver.cpp 0.050 m/pix\n3 2\n255\n", {0, 254, 205, 254, 254, 0}));
  put(dir / "saver.yaml",
      "image: saver.pgm\nresolution: 0.050000\norigin: [-10.000000, -5.500000, 0.000000]\nnegate: 0\n"
      "occupied_thresh: 0.65\nfree_thresh: 0.196\n\n");
  const LoadedMap map = read_map_server(dir / "saver.yaml");
  ASSERT_EQ(map.raster.width, 3);
  ASSERT_EQ(map.raster.height, 2);
  EXPECT_DOUBLE_EQ(map.raster.resolution, 0.05);
  EXPECT_DOUBLE_EQ(map.raster.origin.x(), -10.0);
  EXPECT_DOUBLE_EQ(map.raster.origin.y(), -5.5);
  // Picture top row -> cy = 1.
  const std::vector<std::int8_t> expected{0, 0, 100, 100, 0, -1};
  EXPECT_EQ(map.occupancy, expected);
  EXPECT_FLOAT_EQ(map.raster.at(0, 0).occupancy(), 0.0f);
  EXPECT_FLOAT_EQ(map.raster.at(0, 1).occupancy(), 1.0f);
  EXPECT_FLOAT_EQ(map.raster.at(2, 1).unknown(), 1.0f);
}

TEST(MapServerRead, NegateMakesWhiteOccupied) {
  const fs::path dir = fresh_dir();
  put(dir / "m.pgm", pgm_bytes("P5\n2 1\n255\n", {255, 0}));
  put(dir / "m.yaml", "image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 1\n"
                      "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const LoadedMap map = read_map_server(dir / "m.yaml");
  EXPECT_TRUE(map.options.negate);
  EXPECT_EQ(map.occupancy, (std::vector<std::int8_t>{100, 0}));
  put(dir / "m.yaml", "image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\n"
                      "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  EXPECT_EQ(read_map_server(dir / "m.yaml").occupancy, (std::vector<std::int8_t>{0, 100}));
}

TEST(MapServerRead, PlainPgmWithCommentsAndAbsoluteImagePath) {
  const fs::path dir = fresh_dir();
  put(dir / "plain.pgm", "P2\n# a comment\n2 2 # inline\n255\n0 254\n# between rows\n205 10\n");
  put(dir / "m.yaml", "image: " + fs::absolute(dir / "plain.pgm").string() + "\nresolution: 0.1\n"
                      "origin: [1.5, 2.5, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const LoadedMap map = read_map_server(dir / "m.yaml");
  // Rows: top (cy = 1) = {0, 254} -> {100, 0}; bottom (cy = 0) = {205, 10} -> {-1, 100}.
  EXPECT_EQ(map.occupancy, (std::vector<std::int8_t>{-1, 100, 100, 0}));
}

TEST(MapServerRead, ScaleModeGivesInBetweenValues) {
  const fs::path dir = fresh_dir();
  put(dir / "m.pgm", pgm_bytes("P5\n3 1\n255\n", {128, 0, 254}));
  put(dir / "m.yaml", std::string(kMapYaml) + "mode: scale\n");
  const LoadedMap map = read_map_server(dir / "m.yaml");
  // p = 127/255 = 0.498; ratio (0.498 - 0.196) / (0.65 - 0.196) = 0.665; 99 · 0.665 = 65.8 -> 65.
  EXPECT_EQ(map.occupancy, (std::vector<std::int8_t>{65, 100, 0}));
  EXPECT_NEAR(map.raster.cells[0].occupancy(), 0.65f, 1e-6f);
}

// Expects read_map_server to throw an InputError whose message holds every `parts`.
void expect_input_error(const fs::path& yaml, std::initializer_list<std::string> parts) {
  try {
    read_map_server(yaml);
    ADD_FAILURE() << "no error for " << yaml;
  } catch (const InputError& e) {
    for (const auto& part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(MapServerRead, MissingImageFileNamesItAndTheKey) {
  const fs::path dir = fresh_dir();
  put(dir / "m.yaml", kMapYaml);
  expect_input_error(dir / "m.yaml", {"m.yaml", "'image'", "m.pgm"});
}

TEST(MapServerRead, MissingOrBadKeysAreNamed) {
  const fs::path dir = fresh_dir();
  put(dir / "m.pgm", pgm_bytes("P5\n1 1\n255\n", {0}));
  put(dir / "m.yaml", "image: m.pgm\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
  expect_input_error(dir / "m.yaml", {"m.yaml", "missing key 'resolution'"});
  put(dir / "m.yaml", "image: m.pgm\nresolution: abc\norigin: [0, 0, 0]\nnegate: 0\n"
                      "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  expect_input_error(dir / "m.yaml", {"m.yaml", "line 2", "'resolution'", "abc"});
  put(dir / "m.yaml", "image: m.pgm\nresolution: -0.05\norigin: [0, 0, 0]\nnegate: 0\n"
                      "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  expect_input_error(dir / "m.yaml", {"m.yaml", "'resolution'", "not positive"});
  put(dir / "m.yaml", "image: m.pgm\nresolution: .nan\norigin: [0, 0, 0]\nnegate: 0\n"
                      "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  expect_input_error(dir / "m.yaml", {"m.yaml", "'resolution'", "finite"});
  put(dir / "m.yaml", "image: m.pgm\nresolution: 1\norigin: [0, 0]\nnegate: 0\n"
                      "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  expect_input_error(dir / "m.yaml", {"m.yaml", "'origin'"});
  put(dir / "m.yaml", "image: m.pgm\nresolution: 1\norigin: [0, 0, 0.5]\nnegate: 0\n"
                      "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  expect_input_error(dir / "m.yaml", {"m.yaml", "'origin'", "yaw"});
  put(dir / "m.yaml", "image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: maybe\n"
                      "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  expect_input_error(dir / "m.yaml", {"m.yaml", "'negate'", "maybe"});
  put(dir / "m.yaml", "image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\nfree_thresh: 0.196\n");
  expect_input_error(dir / "m.yaml", {"m.yaml", "'occupied_thresh'"});
  put(dir / "m.yaml", std::string(kMapYaml) + "mode: raw\n");
  expect_input_error(dir / "m.yaml", {"m.yaml", "'mode'", "raw"});
  put(dir / "m.yaml", "image: m.pgm\nresolution: [1\n");
  expect_input_error(dir / "m.yaml", {"m.yaml", "invalid YAML"});
  put(dir / "m.yaml", "- just\n- a list\n");
  expect_input_error(dir / "m.yaml", {"m.yaml", "mapping"});
  expect_input_error(dir / "absent.yaml", {"absent.yaml", "not found"});
}

TEST(MapServerRead, TruncatedOrOversizedPgmIsAnInputError) {
  const fs::path dir = fresh_dir();
  put(dir / "m.yaml", kMapYaml);
  put(dir / "m.pgm", pgm_bytes("P5\n4 3\n255\n", {0, 0, 0, 0, 0}));
  expect_input_error(dir / "m.yaml", {"m.pgm", "truncated"});
  put(dir / "m.pgm", pgm_bytes("P5\n1 1\n255\n", {0, 0}));
  expect_input_error(dir / "m.yaml", {"m.pgm", "size mismatch"});
  put(dir / "m.pgm", "P2\n2 1\n255\n0 0 0\n");
  expect_input_error(dir / "m.yaml", {"m.pgm", "size mismatch"});
  put(dir / "m.pgm", "P2\n3 1\n255\n0 0\n");
  expect_input_error(dir / "m.yaml", {"m.pgm", "truncated"});
  put(dir / "m.pgm", "P6\n1 1\n255\nabc");
  expect_input_error(dir / "m.yaml", {"m.pgm", "not a PGM"});
}

}  // namespace
}  // namespace dsswarm
