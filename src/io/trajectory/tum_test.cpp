#include "io/trajectory/tum.hpp"

#include <gtest/gtest.h>

#include "common/test_files.hpp"

#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

using test::fresh_dir;
using test::write_text;

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs `f`, expecting an InputError whose message contains every piece of `needles`.
template <typename F>
void expect_input_error(F&& f, std::initializer_list<std::string> needles) {
  try {
    f();
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    for (const auto& n : needles) EXPECT_NE(msg.find(n), std::string::npos) << "'" << n << "' not in: " << msg;
  }
}

TEST(Tum, RoundTripKeepsPosesOrderAndWrappedAngles) {
  const fs::path file = fresh_dir("tum_round_trip") / "traj.tum";
  // Backwards timestamp on purpose: file order must survive. Angles near and
  // beyond ±pi exercise the wrap; 2pi + 0.5 is normalised to 0.5 by Pose2.
  const Trajectory original = {
      {976052905.167303, Pose2(1.5, -2.25, 0.3)},     {976052904.9, Pose2(-1234.567891, 0.000001, -3.0)},
      {976052906.0, Pose2(0.0, 0.0, kPi)},            {976052907.5, Pose2(3.0, 4.0, -kPi + 1e-6)},
      {976052908.25, Pose2(-7.0, 8.0, 2 * kPi + 0.5)}, {976052909.0, Pose2(0.1, 0.2, -1.2)},
  };
  write_tum(file, original);
  const Trajectory back = read_tum(file);
  ASSERT_EQ(back.size(), original.size());
  for (std::size_t i = 0; i < back.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_NEAR(back[i].timestamp, original[i].timestamp, 1e-6);
    EXPECT_NEAR(back[i].pose.x, original[i].pose.x, 1e-9);
    EXPECT_NEAR(back[i].pose.y, original[i].pose.y, 1e-9);
    EXPECT_NEAR(normalize_angle(back[i].pose.theta - original[i].pose.theta), 0.0, 1e-8);
  }
  EXPECT_NEAR(back[4].pose.theta, 0.5, 1e-8);
}

TEST(Tum, WritesDocumentedLineFormat) {
  const fs::path file = fresh_dir("tum_format") / "traj.tum";
  write_tum(file, {{12.5, Pose2(1.0, -2.0, kPi / 2)}});
  const std::string text = slurp(file);
  EXPECT_EQ(text,
            "# timestamp x y z qx qy qz qw\n"
            "12.500000 1.000000000 -2.000000000 0.000000 0.000000000 0.000000000 0.707106781 0.707106781\n");
}

TEST(Tum, ReadsThreeDimensionalQuaternionAsYaw) {
  // roll 0.1, pitch 0.2, yaw 1.0 (ZYX). 2*atan2(qz, qw) would give 0.990 here,
  // so this checks the full formula.
  const fs::path file = write_text(fresh_dir("tum_3d") / "traj.tum",
                                   "# written by some 3D tool\n"
                                   "\n"
                                   "100.0 1.0 2.0 0.5 -0.004161148 0.111344157 0.472055466 0.874499171\r\n"
                                   "   \t\n"
                                   "101.0 3 4 0 0 0 0 1\n");
  const Trajectory t = read_tum(file);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_DOUBLE_EQ(t[0].timestamp, 100.0);
  EXPECT_DOUBLE_EQ(t[0].pose.x, 1.0);
  EXPECT_DOUBLE_EQ(t[0].pose.y, 2.0);
  EXPECT_NEAR(t[0].pose.theta, 1.0, 1e-6);
  EXPECT_NEAR(t[1].pose.theta, 0.0, 1e-12);
}

TEST(Tum, QuaternionWithNegativeScalarGivesSameYaw) {
  // q and -q are the same rotation.
  std::istringstream in("1 0 0 0 0 0 -0.479425539 -0.877582562\n");
  const Trajectory t = read_tum(in, "mem");
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR(t[0].pose.theta, 1.0, 1e-8);
}

TEST(Tum, WrongFieldCountNamesFileAndLine) {
  const fs::path file =
      write_text(fresh_dir("tum_bad_count") / "bad.tum", "# header\n1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n");
  expect_input_error([&] { read_tum(file); }, {"bad.tum:3", "expected 8 fields", "found 7"});
}

TEST(Tum, NonNumericFieldNamesLineAndField) {
  const fs::path file = write_text(fresh_dir("tum_bad_num") / "bad.tum", "1 0 0 0 0 0 0 1\n2 0 abc 0 0 0 0 1\n");
  expect_input_error([&] { read_tum(file); }, {"bad.tum:2", "'y'", "abc"});
}

TEST(Tum, NonFiniteAndZeroQuaternionRejected) {
  std::istringstream nan_line("1 nan 0 0 0 0 0 1\n");
  expect_input_error([&] { read_tum(nan_line, "n.tum"); }, {"n.tum:1", "'x'"});
  std::istringstream zero_quat("1 0 0 0 0 0 0 0\n");
  expect_input_error([&] { read_tum(zero_quat, "z.tum"); }, {"z.tum:1", "quaternion"});
}

TEST(Tum, MissingFileAndDirectoryNamed) {
  const fs::path dir = fresh_dir("tum_missing");
  expect_input_error([&] { read_tum(dir / "nope.tum"); }, {"nope.tum", "no such file"});
  expect_input_error([&] { read_tum(dir); }, {"directory"});
}

TEST(Tum, NonFinitePoseIsNotWritten) {
  const fs::path file = fresh_dir("tum_nan_write") / "traj.tum";
  Trajectory t = {{1.0, Pose2(0, 0, 0)}, {2.0, Pose2(0, 0, 0)}};
  t[1].pose.x = std::numeric_limits<double>::quiet_NaN();
  expect_input_error([&] { write_tum(file, t); }, {"traj.tum", "entry 1"});
  EXPECT_FALSE(fs::exists(file));
}

TEST(Tum, EmptyTrajectoryRoundTrips) {
  const fs::path file = fresh_dir("tum_empty") / "traj.tum";
  write_tum(file, {});
  EXPECT_TRUE(read_tum(file).empty());
}

}  // namespace
}  // namespace dsswarm
