#include "io/logs/log_reader.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "common/errors.hpp"
#include "io/logs/logs_test_util.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;

TEST(LogReader, NonBagFilesAreReadAsCarmenWithTheCarmenOptions) {
  const fs::path path = test::scratch_dir("read_log") / "scans.txt";
  test::write_plain(path, "FLASER 3 1 2 3 0 0 0 0 0 0 1.0 host 0\n");
  EXPECT_NEAR(read_log(path).scans.at(0).angle_increment, std::numbers::pi / 2, 1e-12);  // classic, n = 3
  LogReadOptions options;
  options.carmen.beams = CarmenOptions::BeamConvention::Span180;
  options.carmen.laser_offset = Pose2(0.5, 0, 0);
  const LaserScan s = read_log(path, options).scans.at(0);
  EXPECT_NEAR(s.angle_min, -std::numbers::pi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(s.laser_offset.x, 0.5);
}

TEST(LogReader, BagsGoToTheBagReader) {
  // A CARMEN text file named .bag must not be read as CARMEN: the extension decides.
  const fs::path path = test::scratch_dir("read_log_bag") / "scans.BAG";
  test::write_plain(path, "FLASER 3 1 2 3 0 0 0 0 0 0 1.0 host 0\n");
  try {
    read_log(path);
    ADD_FAILURE() << "a text file named .bag was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dsswarm
