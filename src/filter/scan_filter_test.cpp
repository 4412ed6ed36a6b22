// Behaviour of the scan filter on synthetic scans: a tiny ray caster over
// wall segments gives scans of a robot that stands, turns, or walks into a
// new room.
#include "filter/scan_filter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "common/rng.hpp"

namespace dsswarm {
namespace {

struct Wall {
  double x1, y1, x2, y2;
};

// Room A [0,8]x[0,5] with a pillar; a door (y in [2,3]) in its east wall opens
// into the larger room B [8,14]x[-3,9] with two pillars of its own.
std::vector<Wall> two_rooms() {
  std::vector<Wall> walls = {
      {0, 0, 8, 0}, {0, 5, 8, 5}, {0, 0, 0, 5},                     // room A
      {8, 0, 8, 2}, {8, 3, 8, 5},                                   // east wall of A, with the door
      {8, -3, 14, -3}, {8, 9, 14, 9}, {14, -3, 14, 9},              // room B
      {8, -3, 8, 0}, {8, 5, 8, 9},                                  // west wall of B
  };
  auto box = [&walls](double x0, double y0, double x1, double y1) {
    walls.insert(walls.end(), {{x0, y0, x1, y0}, {x1, y0, x1, y1}, {x1, y1, x0, y1}, {x0, y1, x0, y0}});
  };
  box(3.0, 1.0, 3.6, 1.6);
  box(11.0, 5.0, 12.5, 6.0);
  box(12.0, -1.5, 12.4, -1.1);
  return walls;
}

// Distance along the ray from (x, y) at `angle` to the nearest wall, or inf.
double cast(const std::vector<Wall>& walls, double x, double y, double angle) {
  const double dx = std::cos(angle), dy = std::sin(angle);
  double best = std::numeric_limits<double>::infinity();
  for (const Wall& w : walls) {
    const double ex = w.x2 - w.x1, ey = w.y2 - w.y1;
    const double denom = dx * ey - dy * ex;
    if (std::abs(denom) < 1e-12) continue;
    const double t = ((w.x1 - x) * ey - (w.y1 - y) * ex) / denom;  // along the ray
    const double s = ((w.x1 - x) * dy - (w.y1 - y) * dx) / denom;  // along the wall
    if (t > 0.0 && s >= 0.0 && s <= 1.0) best = std::min(best, t);
  }
  return best;
}

// A 181-beam, 180° scan (1° apart, like the intel log) with 1 cm noise; the
// odometry is the true pose unless `with_odometry` is false.
LaserScan scan_at(const Pose2& pose, Rng& rng, bool with_odometry = true) {
  LaserScan scan;
  scan.angle_min = -std::numbers::pi / 2;
  scan.angle_increment = std::numbers::pi / 180.0;
  scan.range_min = 0.05;
  scan.range_max = 30.0;
  const auto walls = two_rooms();
  for (int i = 0; i < 181; ++i) {
    const double r = cast(walls, pose.x, pose.y, pose.theta + scan.beam_angle(static_cast<std::size_t>(i)));
    scan.ranges.push_back(std::isfinite(r) ? static_cast<float>(r + rng.normal(0.0, 0.01)) : 30.0f);
  }
  if (with_odometry) scan.odometry = pose;
  return scan;
}

struct FilterRun {
  std::vector<ScanFilter::Decision> decisions;
  std::size_t kept() const {
    return static_cast<std::size_t>(std::count_if(decisions.begin(), decisions.end(), [](auto& d) { return d.keep; }));
  }
  std::size_t count(const std::string& reason, std::size_t from = 0) const {
    return static_cast<std::size_t>(std::count_if(decisions.begin() + static_cast<std::ptrdiff_t>(from),
                                                  decisions.end(), [&](auto& d) { return reason == d.reason; }));
  }
};

FilterRun run(ScanFilter& filter, const std::vector<LaserScan>& scans) {
  FilterRun r;
  for (const LaserScan& s : scans) {
    r.decisions.push_back(filter.decide(s));
    EXPECT_TRUE(std::isfinite(r.decisions.back().min_correlation));
    EXPECT_TRUE(std::isfinite(r.decisions.back().product));
  }
  return r;
}

std::vector<LaserScan> standing(int count, bool with_odometry = true) {
  Rng rng(7);
  std::vector<LaserScan> scans;
  for (int i = 0; i < count; ++i) scans.push_back(scan_at(Pose2(2.0, 2.5, 0.3), rng, with_odometry));
  return scans;
}

TEST(ScanFilter, StandingRobotDropsNearlyEverythingAfterTheWindow) {
  ScanFilter filter;
  ASSERT_EQ(filter.config().max_consecutive_drops, 5);
  const FilterRun r = run(filter, standing(120));
  // Standing: v = 0, so the largest window (10) fills first.
  EXPECT_EQ(r.decisions.back().window, 10);
  for (std::size_t i = 0; i < 10; ++i) EXPECT_STREQ(r.decisions[i].reason, "window_filling") << i;
  // Afterwards only the consecutive-drop cap keeps a scan: 5 dropped, 1 kept,
  // 18 times over the 110 scans, then 2 dropped.
  EXPECT_EQ(r.count("dissimilar"), 0u);
  EXPECT_EQ(r.count("drop_cap"), 18u);
  EXPECT_EQ(filter.dropped(), 92u);
  EXPECT_EQ(filter.kept(), 28u);
  EXPECT_GT(r.decisions.back().min_correlation, 0.99);
}

TEST(ScanFilter, WithoutOdometryTheWindowIsFixed) {
  ScanFilter filter;
  const FilterRun r = run(filter, standing(40, false));
  for (const auto& d : r.decisions) EXPECT_EQ(d.window, 5);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_STREQ(r.decisions[i].reason, "window_filling");
  EXPECT_GE(filter.dropped(), 30u);
  EXPECT_FALSE(filter.speed_cm_per_scan().has_value());
}

TEST(ScanFilter, RotatingRobotKeepsItsScans) {
  // Turning in place by 3 beams (3°) per scan; the motion valve is off so
  // only the histogram comparison can keep scans.
  ScanFilterConfig config;
  config.max_rotation = std::numeric_limits<double>::infinity();
  ScanFilter filter(config);
  Rng rng(3);
  std::vector<LaserScan> scans;
  for (int i = 0; i < 60; ++i) scans.push_back(scan_at(Pose2(2.0, 2.5, 0.05 * i), rng));
  const FilterRun r = run(filter, scans);
  EXPECT_EQ(r.count("drop_cap"), 0u);
  EXPECT_GE(r.count("dissimilar"), 40u);
  EXPECT_LE(filter.dropped(), 12u);
}

TEST(ScanFilter, RobotEnteringANewRoomKeepsScans) {
  // Walking east 5 cm per scan through the door from room A into room B;
  // valves off. 10 columns (18-degree sectors): with the default 6 for this
  // 181-beam scan, the door, which fills about half of one 30-degree sector
  // while crossing room A, flips that sector's median between the near wall
  // and the far room every few steps, and room A keeps as many scans as the
  // doorway (the price of the coarser default, README "Scan filter").
  ScanFilterConfig config;
  config.columns = 10;
  config.max_translation = std::numeric_limits<double>::infinity();
  config.max_consecutive_drops = 1000;
  ScanFilter filter(config);
  Rng rng(5);
  std::vector<LaserScan> scans;
  for (int i = 0; i <= 120; ++i) scans.push_back(scan_at(Pose2(5.0 + 0.05 * i, 2.5, 0.0), rng));
  const FilterRun r = run(filter, scans);
  // The door frame (x = 8, scan 60) comes into the side sectors from x ~ 7
  // (scan 40) on: from there the view changes quickly and scans are kept far
  // more often than while crossing room A, where one kept scan stands for
  // dozens of 5 cm steps (each drop compares with the last kept scan, so a
  // slow drift still ends in a kept scan).
  std::size_t kept_in_a = 0, kept_near_door = 0;
  for (std::size_t i = 10; i < 34; ++i) kept_in_a += r.decisions[i].keep ? 1 : 0;
  for (std::size_t i = 38; i < 62; ++i) kept_near_door += r.decisions[i].keep ? 1 : 0;
  EXPECT_GE(kept_near_door, 6u);
  EXPECT_GE(kept_near_door, 3 * kept_in_a);
  EXPECT_EQ(r.count("drop_cap") + r.count("moved"), 0u);
}

TEST(ScanFilter, ConstantHistogramsAreIdenticalAndAChangeIsKept) {
  // All readings invalid: constant (all-zero) histograms, correlation 1 with each other.
  LaserScan blind;
  blind.range_min = 0.05;
  blind.range_max = 30.0;
  blind.ranges.assign(181, std::numeric_limits<float>::quiet_NaN());
  ScanFilter filter;
  std::vector<LaserScan> scans(12, blind);
  Rng rng(1);
  scans.push_back(scan_at(Pose2(2.0, 2.5, 0.3), rng, false));  // the lidar sees again
  const FilterRun r = run(filter, scans);
  for (std::size_t i = 5; i < 10; ++i) {
    EXPECT_FALSE(r.decisions[i].keep) << i;
    EXPECT_EQ(r.decisions[i].min_correlation, 1.0);
  }
  EXPECT_STREQ(r.decisions[10].reason, "drop_cap");  // 5 in a row: the cap
  EXPECT_TRUE(r.decisions.back().keep);
  EXPECT_STREQ(r.decisions.back().reason, "dissimilar");
  EXPECT_EQ(r.decisions.back().min_correlation, 0.0);
}

TEST(ScanFilter, NaNRangesAreSkipped) {
  // Beams that never return (every 5th, and a 20-beam block: whole empty
  // columns) change nothing: the standing robot's scans are still dropped.
  std::vector<LaserScan> scans = standing(40);
  for (LaserScan& s : scans) {
    for (std::size_t i = 0; i < s.ranges.size(); ++i) {
      if (i % 5 == 0 || (i >= 100 && i < 120)) s.ranges[i] = std::numeric_limits<float>::quiet_NaN();
    }
  }
  ScanFilter filter;
  run(filter, scans);  // checks every correlation is finite
  // 30 scans after the window of 10: 5 dropped, 1 kept (cap), four more
  // times, then 5 dropped.
  EXPECT_EQ(filter.dropped(), 25u);

  // Random dropouts (20% of the beams) move sector medians, but never give NaN.
  Rng rng(11);
  for (LaserScan& s : scans) {
    for (float& range : s.ranges) {
      if (rng.uniform() < 0.2) range = std::numeric_limits<float>::quiet_NaN();
    }
  }
  ScanFilter random_dropouts;
  const FilterRun r = run(random_dropouts, scans);
  for (const auto& d : r.decisions) {
    EXPECT_GE(d.min_correlation, -1.0);
    EXPECT_LE(d.product, 1.0);
  }
}

TEST(ScanFilter, ConsecutiveDropCap) {
  ScanFilterConfig config;
  config.max_consecutive_drops = 3;
  ScanFilter filter(config);
  const FilterRun r = run(filter, standing(50));
  int in_a_row = 0, longest = 0;
  for (std::size_t i = 10; i < r.decisions.size(); ++i) {
    in_a_row = r.decisions[i].keep ? 0 : in_a_row + 1;
    longest = std::max(longest, in_a_row);
    if (r.decisions[i].keep) {
      EXPECT_STREQ(r.decisions[i].reason, "drop_cap");
    }
  }
  EXPECT_EQ(longest, 3);
  EXPECT_EQ(filter.dropped(), 30u);  // 40 after the window, in groups of 3 dropped + 1 kept

  config.max_consecutive_drops = 0;  // filter off
  ScanFilter off(config);
  run(off, standing(30));
  EXPECT_EQ(off.dropped(), 0u);
}

TEST(ScanFilter, OdometryMotionSinceTheLastKeptScanKeepsTheScan) {
  // The same view while odometry says the robot moves 12 cm per scan (a
  // featureless corridor, say): every third scan is past 0.35 m and kept.
  ScanFilterConfig config;
  config.max_translation = 0.35;
  config.max_consecutive_drops = 10;
  std::vector<LaserScan> scans = standing(30);
  for (std::size_t i = 0; i < scans.size(); ++i) scans[i].odometry = Pose2(0.12 * double(i), 0.0, 0.0);
  ScanFilter moving(config);
  const FilterRun r = run(moving, scans);
  EXPECT_EQ(r.decisions.back().window, 1);  // v = 12 cm: 27 / 144 rounds to 0, clamped to 1
  for (std::size_t i = 1; i < scans.size(); ++i) {
    EXPECT_EQ(r.decisions[i].keep, i % 3 == 0) << i;
  }
  EXPECT_GT(r.count("moved"), 5u);

  // Turning 0.08 rad per scan: 0.24 rad after 3 scans exceeds 0.2.
  for (std::size_t i = 0; i < scans.size(); ++i) scans[i].odometry = Pose2(0.0, 0.0, 0.08 * double(i));
  ScanFilter turning(config);
  const FilterRun t = run(turning, scans);
  EXPECT_GT(t.count("moved"), 5u);
  EXPECT_EQ(t.count("drop_cap"), 0u);
  for (std::size_t i = 10; i < scans.size(); ++i) {
    if (t.decisions[i].keep) {
      EXPECT_STREQ(t.decisions[i].reason, "moved");
    }
  }
}

TEST(ScanFilter, OdometryThatTheScansContradictIsNotTrusted) {
  // Backing up west 5 cm per scan, facing the east wall of room A, while
  // odometry claims 5 cm forward (fr079's odometry does this): the wall ahead
  // recedes instead of approaching, so no scan is dropped on that odometry.
  Rng rng(9);
  std::vector<LaserScan> truthful, lying;
  for (int i = 0; i < 40; ++i) {
    LaserScan s = scan_at(Pose2(6.5 - 0.05 * i, 4.0, 0.0), rng);
    truthful.push_back(s);
    s.odometry = Pose2(4.5 + 0.05 * i, 4.0, 0.0);
    lying.push_back(s);
  }
  ScanFilter honest;
  const FilterRun h = run(honest, truthful);
  EXPECT_GE(honest.dropped(), 10u);
  EXPECT_EQ(h.count("odometry_doubt"), 0u);

  ScanFilter doubting;
  const FilterRun l = run(doubting, lying);
  EXPECT_GE(l.count("odometry_doubt"), 30u);
  EXPECT_LE(doubting.dropped(), 2u);

  ScanFilterConfig off;
  off.doubt_ratio = std::numeric_limits<double>::infinity();
  ScanFilter trusting(off);
  const FilterRun t = run(trusting, lying);
  EXPECT_EQ(t.count("odometry_doubt"), 0u);
  EXPECT_GE(trusting.dropped(), 10u);
}

TEST(ScanFilter, WindowFollowsTheSpeedByEquationSeven) {
  // 27 / v^2 with v in cm per scan, rounded, clamped to [1, 10].
  const std::vector<std::pair<double, int>> cases = {{1.0, 10}, {2.0, 7}, {3.0, 3}, {0.5, 10}, {4.0, 2},
                                                     {5.0, 1}, {19.0, 1}};
  for (const auto& [cm, window] : cases) {
    ScanFilter filter;
    std::vector<LaserScan> scans = standing(5);
    for (std::size_t i = 0; i < scans.size(); ++i) scans[i].odometry = Pose2(0.01 * cm * double(i), 0.0, 0.0);
    const FilterRun r = run(filter, scans);
    EXPECT_EQ(r.decisions.back().window, window) << cm << " cm per scan";
    EXPECT_NEAR(*filter.speed_cm_per_scan(), cm, 1e-9);
  }
}

TEST(ScanFilter, StricterCommonThresholdKeepsMore) {
  ScanFilterConfig strict;
  strict.common_threshold = 0.99999;
  ScanFilter filter(strict);
  run(filter, standing(40));
  ScanFilter normal;
  run(normal, standing(40));
  EXPECT_LT(filter.dropped(), normal.dropped());
}

TEST(ScanFilterConfig, ValidateNamesTheField) {
  auto expect_field = [](const ScanFilterConfig& c, const std::string& field) {
    try {
      c.validate();
      ADD_FAILURE() << "no error for " << field;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
    EXPECT_THROW(ScanFilter{c}, ConfigError);
  };
  EXPECT_NO_THROW(ScanFilterConfig{}.validate());
  ScanFilterConfig c;
  c.columns = 2;
  expect_field(c, "columns");
  c = {};
  c.pair_threshold = 0.9;
  expect_field(c, "pair_threshold");
  c.pair_threshold = std::numeric_limits<double>::quiet_NaN();
  expect_field(c, "pair_threshold");
  c = {};
  c.common_threshold = 1.5;
  expect_field(c, "common_threshold");
  c = {};
  c.window_constant = 0.0;
  expect_field(c, "window_constant");
  c = {};
  c.min_window = 0;
  expect_field(c, "min_window");
  c = {};
  c.max_window = 0;
  expect_field(c, "max_window");
  c = {};
  c.fixed_window = 0;
  expect_field(c, "fixed_window");
  c = {};
  c.speed_samples = 0;
  expect_field(c, "speed_samples");
  c = {};
  c.max_consecutive_drops = -1;
  expect_field(c, "max_consecutive_drops");
  c = {};
  c.max_translation = 0.0;
  expect_field(c, "max_translation");
  c = {};
  c.max_rotation = -0.1;
  expect_field(c, "max_rotation");
  c = {};
  c.doubt_ratio = -0.5;
  expect_field(c, "doubt_ratio");
  c = {};
  c.doubt_min_travel = -0.01;
  expect_field(c, "doubt_min_travel");
  c = {};
  c.doubt_cone = 0.0;
  expect_field(c, "doubt_cone");
}

}  // namespace
}  // namespace dsswarm
